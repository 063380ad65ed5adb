"""core/coords.py: Blender (+Z up) <-> facet (+Y up), float32-clean numbers, 4x4 matrices."""

import math
import random
import struct

import pytest

from facet_blender.core import coords


def test_axes_map_up_to_up_and_back():
    assert coords.to_facet([0, 0, 1]) == [0.0, 1.0, -0.0]          # Blender up is facet up
    assert coords.to_facet([0, 1, 0]) == [0.0, 0.0, -1.0]          # Blender forward (+Y) is facet −Z
    rng = random.Random(1)
    for _ in range(20):
        v = [rng.uniform(-5, 5) for _ in range(3)]
        assert coords.to_blender(coords.to_facet(v)) == v


def test_the_axis_change_is_a_rotation():
    a, b = [1.0, 2.0, 3.0], [-0.5, 0.25, 2.0]
    # cross products and lengths survive: windings and normals stay as they are
    assert coords.to_facet(coords.cross(a, b)) == pytest.approx(coords.cross(coords.to_facet(a), coords.to_facet(b)))
    assert coords.dot(coords.to_facet(a), coords.to_facet(b)) == pytest.approx(coords.dot(a, b))


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


@pytest.mark.parametrize("typed", [0.3, 0.1, 1.7, 123.456, 1e-5, 0.04, 2.2, -0.35])
def test_clean_float_gives_back_what_was_typed(typed):
    assert coords.clean_float(f32(typed)) == typed


def test_clean_float_keeps_values_that_are_not_float32():
    x = 1.0 / 3.0
    assert coords.clean_float(x) == x
    assert coords.clean_float(0.0) == 0.0 and coords.clean_float(-0.0) == 0.0
    assert math.isinf(coords.clean_float(float("inf")))
    assert coords.clean_float(1e300) == 1e300
    assert coords.clean_vector([f32(0.3), 1]) == [0.3, 1.0]


def test_normalize_refuses_zero():
    assert coords.normalize([3.0, 0.0, 4.0]) == [0.6, 0.0, 0.8]
    with pytest.raises(ValueError):
        coords.normalize([0.0, 0.0, 0.0])


def test_matrices():
    m = [[2.0, 0.0, 0.0, 1.0], [0.0, 0.0, -3.0, 2.0], [0.0, 1.0, 0.0, 3.0], [0, 0, 0, 1]]
    assert coords.transform_point(m, [1, 1, 1]) == [3.0, -1.0, 4.0]
    assert coords.transform_direction(m, [1, 1, 1]) == [2.0, -3.0, 1.0]
    assert coords.det3(m) == pytest.approx(6.0)
    assert coords.column_scale(m) == pytest.approx([2.0, 1.0, 3.0])
    n = coords.normal_matrix(m)
    # the inverse transpose: n^T · m = identity on the upper 3x3
    for i in range(3):
        for j in range(3):
            assert sum(n[k][i] * m[k][j] for k in range(3)) == pytest.approx(1.0 if i == j else 0.0)
    with pytest.raises(ValueError):
        coords.normal_matrix([[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
