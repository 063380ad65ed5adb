#!/usr/bin/env python3
"""Tabulates E(μ, r), the directional albedo of KHR_materials_sheen's sheen BRDF, for facet's fit
of it (codegen/catalog/sheen_albedo_table.inc), and measures the fit against the integral.

The sheen BRDF is the README's ("Implementation Notes": the "Charlie" distribution D_s and the
"Charlie" visibility ν_s of Conty & Kulla 2017, α_g = sheenRoughness², floored at facet's 1e-3),
and its albedo scaling reads E at n·v and at n·l ("Albedo-scaling technique"). E is

    E(μ, r) = ∫ D_s(h) ν_s(l, v) (n·l) dω_l      (sheenColor 1; v at cosine μ from n)

integrated here on a midpoint grid in (n·l)^⅙ and φ. The fit, identical on every target because it is
printed as code, is a Chebyshev series in two variables, one piece of μ × one piece of r at a time:
μ in three pieces, [10⁻³, 0.15], [0.15, 0.5] (lambda_sheen changes formula at a cosine of 0.5, a kink
in E) and [0.5, 1], the series in μ^¼ (the first piece) or √μ; r in three pieces, [√10⁻³, 0.1],
[0.1, 0.3] and [0.3, 1] (E changes fastest at small r), the series in √r; degree 9 in each, the
interpolant of log(E + 1e-4) at the 10 × 10 Gauss–Chebyshev nodes of the two. E = clamp(exp(series)
− 1e-4, 0, 1); below μ = 10⁻³ E is E(10⁻³) (E grows as 1/μ toward 0), and r is clamped into [√10⁻³, 1].
A material whose sheen roughness is a number has the r series summed when its code is generated
(catalog/sheen.cpp); one whose roughness is an image (sheenRoughnessTexture) sums it at every pixel,
the same coefficients: the same E either way.

min(·, 1): the integral exceeds 1 at grazing views below a sheen roughness of about 0.3 (the
visibility fit is not energy conserving there; up to 6 at μ = 10⁻³ and the floor), where the
scaling 1 − max₃(c) E would turn the base negative; facet's E is min(∫, 1).

Run it (numpy only; a few minutes) after changing the formula: it integrates the fit's
nodes and, independently, a check grid (62 roughnesses × 53 cosines, most of them off the fit's
rows and nodes), and prints and writes the fit's worst error on the check grid.
tests/unit/gltf_pbr_test.cpp checks the fit against an integral of its own.
"""
import argparse
import pathlib
import sys

import numpy as np

ALPHA_MIN = 1e-3  # catalog.h kRoughnessMin
R_MIN = ALPHA_MIN ** 0.5
EPSILON = 1e-4
# Below μ = 10⁻³ E is read at 10⁻³ (E grows as 1/μ toward 0: Λ(0) is finite).
MU_MIN = 1e-3
MU_PIECES = [MU_MIN, 0.15, 0.5, 1.0]
# Each piece's series is in μ^q: near 0 E has a term in μ^c, c ≈ 0.17–0.2 (the README's l(x)).
POWERS = [0.25, 0.5, 0.5]
NODES = 10
# The pieces of sheen roughness, each a series in r^R_POWER.
R_PIECES = [R_MIN, 0.1, 0.3, 1.0]
R_POWER = 0.5
R_NODES = 10
# The check grid, off most of the rows and nodes.
MUS = np.concatenate([np.linspace(0.001, 0.1, 23), np.linspace(0.11, 1, 30)])


def l_fit(x, a):
    """The README's l(x, alpha_g)."""
    t = (1 - a) ** 2
    mix = lambda p, q: p + (q - p) * t  # noqa: E731
    return (mix(21.5473, 25.3245) / (1 + mix(3.82987, 3.32435) * x ** mix(0.19823, 0.16801))
            + mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967))


def lambda_sheen(c, a):
    c = np.abs(c)
    return np.where(c < 0.5, np.exp(l_fit(c, a)), np.exp(2 * l_fit(0.5, a) - l_fit(1 - c, a)))


def albedo(mu, r, n=300):
    """E(μ, r): a midpoint grid over t ∈ (0, 1), n·l = t⁶, and φ_l ∈ (0, π) (the integrand is even in
    φ); dω = d(n·l) dφ = 6 t⁵ dt dφ. The substitution smooths the (n·l)^c, c ≈ 0.2, of Λ(n·l): the
    grid converges as 1/n² (to about 1e-5 at n = 300 where E is below 1)."""
    a = max(r * r, ALPHA_MIN)
    t = (np.arange(n) + 0.5) / n
    ph = (np.arange(2 * n) + 0.5) / (2 * n) * np.pi
    T, P = np.meshgrid(t, ph, indexing="ij")
    lz = T ** 6
    s = np.sqrt(1 - lz * lz)
    lx, ly = s * np.cos(P), s * np.sin(P)
    vx, vz = np.sqrt(1 - mu * mu), mu
    hx, hy, hz = lx + vx, ly, lz + vz
    noh = hz / np.sqrt(hx * hx + hy * hy + hz * hz)
    inv = 1 / a
    d = (2 + inv) * np.maximum(1 - noh * noh, 0) ** (inv * 0.5) / (2 * np.pi)
    v = 1 / ((1 + lambda_sheen(mu, a) + lambda_sheen(lz, a)) * (4 * mu * lz))
    return 2 * (d * v * lz * 6 * T ** 5).sum() * (1 / n) * (np.pi / (2 * n))


def check_rows():
    """The check grid's sheen roughnesses: every 0.025, and 24 between the floor and 0.2."""
    rs = set(np.round(np.linspace(0, 1, 41), 6)) | set(np.round(np.linspace(R_MIN, 0.2, 24), 6))
    return np.array(sorted({round(max(r, R_MIN), 6) for r in rs}))


def chebyshev(x, n):
    out = [np.ones_like(x), x]
    for _ in range(2, n + 1):
        out.append(2 * x * out[-1] - out[-2])
    return out[: n + 1]


def gauss_nodes(n=NODES):
    """x_j = cos(π (j + ½) / n)."""
    return np.cos(np.pi * (np.arange(n) + 0.5) / n)


def piece_points(pieces, powers, n):
    """Each piece's points at the Gauss nodes (the point^q linear in x)."""
    x = gauss_nodes(n)
    return np.array([(lo ** q + (x + 1) / 2 * (hi ** q - lo ** q)) ** (1 / q)
                     for lo, hi, q in zip(pieces[:-1], pieces[1:], powers)])


def coefficients(y, axis):
    """Chebyshev coefficients of the interpolant through y at the Gauss nodes along `axis` (a_0 halved)."""
    n = y.shape[axis]
    k = np.arange(n)[:, None]
    j = np.arange(n)[None, :]
    a = np.moveaxis(np.tensordot(2 / n * np.cos(np.pi * k * (j + 0.5) / n), y, axes=(1, axis)), 0, axis)
    first = [slice(None)] * y.ndim
    first[axis] = 0
    a[tuple(first)] /= 2
    return a


def argument(v, pieces, powers):
    """The piece v lies in and v^q mapped onto [−1, 1] there."""
    p = min(int(np.searchsorted(pieces, v, side="right")) - 1, len(pieces) - 2)
    q = powers[p]
    lo, hi = pieces[p] ** q, pieces[p + 1] ** q
    return p, 2 * (v ** q - lo) / (hi - lo) - 1


def fit(c, mu, r):
    """facet's E(μ, r), as catalog/sheen.cpp computes it: c[r piece][μ piece][k (μ)][j (r)]."""
    rp, y = argument(min(max(r, R_MIN), 1.0), R_PIECES, [R_POWER] * (len(R_PIECES) - 1))
    p, x = argument(max(mu, MU_MIN), MU_PIECES, POWERS)
    a = c[rp][p] @ np.array(chebyshev(np.array(y), R_NODES - 1))
    s = a @ np.array(chebyshev(np.array(x), NODES - 1))
    return float(np.clip(np.exp(s) - EPSILON, 0, 1))


def cached(path, shape, compute):
    if path and path.exists():
        data = np.load(path)["grid"]
        assert data.shape == shape, f"{path}: another shape"
        return data
    grid = compute()
    if path:
        np.savez(path, grid=grid)
    return grid


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", type=pathlib.Path,
                    default=pathlib.Path(__file__).resolve().parent.parent / "codegen/catalog/sheen_albedo_table.inc")
    ap.add_argument("--cache", type=pathlib.Path, help="a folder for the integrals: read where they are, else written")
    args = ap.parse_args()
    if args.cache:
        args.cache.mkdir(parents=True, exist_ok=True)
    node_mus = piece_points(MU_PIECES, POWERS, NODES)
    node_rs = piece_points(R_PIECES, [R_POWER] * (len(R_PIECES) - 1), R_NODES)

    def table_integrals():
        out = np.zeros(node_rs.shape + node_mus.shape)
        for i, rows in enumerate(node_rs):
            for j, r in enumerate(rows):
                out[i, j] = [[albedo(m, r) for m in piece] for piece in node_mus]
                print(f"  node r = {r:.4f} ({i * R_NODES + j + 1}/{node_rs.size})", file=sys.stderr, flush=True)
        return out

    rs = check_rows()

    def check_integrals():
        out = np.zeros((len(rs), len(MUS)))
        for i, r in enumerate(rs):
            out[i] = [albedo(m, r) for m in MUS]
            print(f"  check row r = {r:.4f} ({i + 1}/{len(rs)})", file=sys.stderr, flush=True)
        return out

    table_e = cached(args.cache / "nodes.npz" if args.cache else None, node_rs.shape + node_mus.shape, table_integrals)
    check_e = cached(args.cache / "check.npz" if args.cache else None, (len(rs), len(MUS)), check_integrals)
    # [r piece][r node][μ piece][μ node] → c[r piece][μ piece][k][j].
    c = coefficients(coefficients(np.log(table_e + EPSILON), axis=1), axis=3).transpose(0, 2, 3, 1)
    err = np.array([[abs(fit(c, m, r) - min(e, 1)) for m, e in zip(MUS, row)] for r, row in zip(rs, check_e)])
    worst, worst_above = err.max(), err[rs >= 0.1].max()
    i, j = np.unravel_index(err.argmax(), err.shape)
    print(f"worst |fit − min(∫, 1)| on the check grid: {worst:.2e} (at r = {rs[i]:.4f}, μ = {MUS[j]:.3f}); "
          f"{worst_above:.2e} for r ≥ 0.1")
    def nested(a):
        if a.ndim == 1:
            return "{" + ", ".join(f"{v:.17g}" for v in a) + "}"
        return "{" + ",\n     ".join(nested(b) for b in a) + "}"

    text = f"""// Generated by scripts/fit_sheen_albedo.py; do not edit. log(E + {EPSILON:g}) of KHR_materials_sheen's
// directional albedo E(μ, r) (Charlie D and visibility, α = max(r², 1e-3)) as Chebyshev series in
// μ^q (q = kSheenAlbedoPowers) and r^{R_POWER:g} on pieces of each: coefficient [r piece][μ piece][k][j] of
// T_k(x(μ)) T_j(y(r)). Worst |fit − min(∫, 1)| on a check grid of {len(rs)} roughnesses × {len(MUS)} cosines:
// {worst:.1e} ({worst_above:.1e} for r ≥ 0.1).
inline constexpr int kSheenAlbedoNodes = {NODES};
inline constexpr int kSheenAlbedoRNodes = {R_NODES};
inline constexpr double kSheenAlbedoEpsilon = {EPSILON:g};
inline constexpr double kSheenAlbedoWorstError = {worst:.2e};
inline constexpr double kSheenAlbedoMuPieces[] = {{{", ".join(f"{p:g}" for p in MU_PIECES)}}};
inline constexpr double kSheenAlbedoPowers[] = {{{", ".join(f"{q:g}" for q in POWERS)}}};
inline constexpr double kSheenAlbedoRPieces[] = {{{", ".join(f"{p:.17g}" for p in R_PIECES)}}};
inline constexpr double kSheenAlbedoRPower = {R_POWER:g};
inline constexpr double kSheenAlbedoCoefficients[{len(R_PIECES) - 1}][{len(MU_PIECES) - 1}][{NODES}][{R_NODES}] = {nested(c)};
"""
    args.output.write_text(text)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
