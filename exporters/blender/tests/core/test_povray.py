"""core/povray.py: finding POV-Ray and rendering facet's scenes (one run, or one run per pass)."""

import json
import os
import struct
import subprocess
import time

import pytest

from facet_blender.core import UserError, pov, povray
from support import alive, example, left_alive, read_png, script

# A stand-in POV-Ray: writes a 16-bit PPM (+FP16) whose samples are the light index + 2
# times 1000 (the run's Declare=Facet_Light=i; 1000 for a plain run), so the sum tells
# which passes were added. Every call is logged.
FAKE_POVRAY = r"""
log="$(dirname "$0")/calls.log"
echo "$*" >> "$log"
light=-1; out=""; width=0; height=0
for a; do
  case "$a" in
    +O*) out="${a#+O}";;
    +W*) width="${a#+W}";;
    +H*) height="${a#+H}";;
    Declare=Facet_Light=*) light="${a#Declare=Facet_Light=}";;
  esac
done
case "$*" in *FAIL_ON_$light*) echo "Parse Error: simulated in pass $light" >&2; exit 3;; esac
value=$(( (light + 2) * 1000 ))
case "$*" in
  *+FP16*) python3 -c "import struct,sys; w,h,v=map(int,sys.argv[1:4]); sys.stdout.buffer.write(b'P6\n%d %d\n65535\n' % (w, h) + struct.pack('>%dH' % (3*w*h), *([v]*(3*w*h))))" $width $height $value > "$out";;
esac
"""


@pytest.fixture
def fake(tmp_path):
    folder = tmp_path / "bin"
    folder.mkdir()
    return script(folder / "povray", FAKE_POVRAY)


def scene_file(tmp_path, text="#declare Facet_Exposure = 1;\n"):
    path = tmp_path / "scene.pov"
    path.write_text(text)
    return str(path)


def calls(fake):
    with open(os.path.join(os.path.dirname(fake), "calls.log")) as f:
        return f.read().splitlines()


def test_find_povray(tmp_path, fake, monkeypatch):
    assert povray.find_povray(fake) == fake
    monkeypatch.setenv("PATH", os.path.dirname(fake))
    assert povray.find_povray("") == fake and povray.default_povray_path() == fake
    assert povray.find_povray("povray") == fake
    with pytest.raises(UserError) as e:
        povray.find_povray(str(tmp_path / "none"))
    assert "POV-Ray not found at" in str(e.value) and povray.PREFERENCES_HINT in str(e.value)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(UserError, match="POV-Ray not found: install POV-Ray 3.7"):
        povray.find_povray("")


def test_a_scene_without_facets_plan_is_refused(tmp_path, fake):
    pov_path = scene_file(tmp_path, "#declare Facet_Passes = 3;\n")         # the declaration is not read
    with pytest.raises(UserError, match="did not say how many POV-Ray runs"):
        povray.render(fake, pov_path, None, str(tmp_path / "out.png"), 4, 3)
    assert not os.path.exists(os.path.join(os.path.dirname(fake), "calls.log"))


def test_one_run(tmp_path, fake):
    png = tmp_path / "out.png"
    assert povray.render(fake, scene_file(tmp_path), pov.Plan(1, True), str(png), 4, 3) == 1
    assert read_png(str(png)) == (4, 3, 16, [1000] * 36)
    (call,) = calls(fake)
    args = call.split()
    assert args[0] == "+Iscene.pov" and args[1].startswith("+O.facet-pov-") and "+FP16" in args
    assert "File_Gamma=1.0" in call and "Facet_Light" not in call and "Facet_Exposure" not in call
    assert "-A" in args and "+Q9" in args and not any(a.startswith(("+AM", "+R")) for a in args)   # EXACT
    assert sorted(os.listdir(tmp_path)) == ["bin", "out.png", "scene.pov"]


def test_passes_are_rendered_one_per_light_and_added(tmp_path, fake):
    png = tmp_path / "out.png"
    assert povray.render(fake, scene_file(tmp_path), pov.Plan(3, False, "meshes"), str(png), 4, 3, 0.5) == 3
    assert read_png(str(png)) == (4, 3, 16, [(2 + 3 + 4) * 1000] * 36)     # lights 0, 1, 2
    runs = calls(fake)
    assert sorted(next(a for a in c.split() if a.startswith("Declare=Facet_Light")) for c in runs) == [
        f"Declare=Facet_Light={i}" for i in range(3)]
    assert all("+FP16" in c and "Declare=Facet_Exposure=0.5" in c for c in runs)
    assert sorted(os.listdir(tmp_path)) == ["bin", "out.png", "scene.pov"]


def test_anti_aliasing_and_quality_options(tmp_path, fake):
    settings = povray.Settings(antialias=True, threshold=0.1, depth=4, method=1, quality=5)
    povray.render(fake, scene_file(tmp_path), pov.Plan(2, False), str(tmp_path / "out.png"), 4, 3, settings=settings)
    for call in calls(fake):
        args = call.split()
        assert "-A" not in args and {"+A0.1", "+AM1", "+R4", "+Q5"} <= set(args), call


# Writes its image halfway, says how far it got (as POV-Ray's +V does), then sleeps in a
# child process (`sleep`, its own pid in children.log): killing only the script would leave it.
SLOW_POVRAY = r"""
folder="$(dirname "$0")"
pwd >> "$folder/cwd.log"
echo "Rendered 6 of 12 pixels (50%)" >&2
sleep 60 &
echo $! >> "$folder/children.log"
wait
"""


def test_a_job_is_polled_and_closing_it_kills_every_run_and_its_children(tmp_path):
    folder = tmp_path / "bin"
    folder.mkdir()
    slow = script(folder / "povray", SLOW_POVRAY)
    job = povray.Job(slow, scene_file(tmp_path), pov.Plan(3, False), 4, 3)
    job.at_once = 2
    assert not job.poll()
    for _ in range(100):                                       # until both runs have said how far they got
        if abs(job.progress() - 1.0 / 3) < 1e-9:
            break
        time.sleep(0.05)
    assert abs(job.progress() - 1.0 / 3) < 1e-9                # 2 runs at 50 % of 3 passes
    assert not job.poll() and len(job.running) == 2 and job.waiting == [2]
    children = [int(p) for p in (folder / "children.log").read_text().split()]
    runs = [r.proc.pid for r in job.running]
    assert len(children) == 2 and all(alive(p) for p in children + runs)
    job.close()
    assert not any(alive(p) for p in runs)                     # close() waited for them
    assert not left_alive(children), "a run's child outlived close()"
    assert sorted(os.listdir(tmp_path)) == ["bin", "scene.pov"]          # the temporary folder is gone


# A stand-in POV-Ray that reports half its pixels, then prints more than the 512 bytes progress
# reads of the log's tail (POV-Ray's statistics at the end of a render) and waits before it exits.
TALKATIVE_POVRAY = r"""
echo "Rendered 6 of 12 pixels (50%)"
sleep 0.3
python3 -c "print('Render Statistics: ' + 'x' * 2000)"
sleep 30
"""


def test_a_runs_progress_never_goes_back(tmp_path):
    """Once POV-Ray's statistics push its last progress line out of the log's tail, the run still
    counts as far as it said (Blender's progress bar went 0.17 → 0 before: the engine test failed)."""
    folder = tmp_path / "bin"
    folder.mkdir()
    talkative = script(folder / "povray", TALKATIVE_POVRAY)
    job = povray.Job(talkative, scene_file(tmp_path), pov.Plan(1, False), 4, 3)
    try:
        job.poll()
        seen = []
        for _ in range(60):
            seen.append(job.progress())
            if len(seen) > 5 and seen[-1] == 0.5 and "Rendered" not in job.running[0]._tail(512):
                break
            time.sleep(0.05)
        assert seen == sorted(seen) and seen[-1] == 0.5, seen
    finally:
        job.close()


def test_a_failing_pass_is_named_and_leaves_the_old_png(tmp_path, fake):
    png = tmp_path / "out.png"
    png.write_text("old image")
    pov_path = scene_file(tmp_path, "// FAIL_ON_1\n#declare Facet_Exposure = 1;\n")
    os.rename(pov_path, tmp_path / "FAIL_ON_1.pov")                          # the fake reads its arguments
    with pytest.raises(UserError) as e:
        povray.render(fake, str(tmp_path / "FAIL_ON_1.pov"), pov.Plan(2, False), str(png), 4, 3)
    text = str(e.value)
    assert "POV-Ray failed (pass 2 of 2; exit status 3)" in text and "simulated in pass 1" in text
    assert png.read_text() == "old image"
    assert sorted(os.listdir(tmp_path)) == ["FAIL_ON_1.pov", "bin", "out.png"]


def test_exposure_needs_the_declaration(tmp_path, fake):
    pov_path = scene_file(tmp_path, "// an older facet\n")
    with pytest.raises(UserError, match="does not declare Facet_Exposure"):
        povray.render(fake, pov_path, pov.Plan(1, True), str(tmp_path / "out.png"), 4, 3, exposure=0.25)
    povray.render(fake, pov_path, pov.Plan(1, True), str(tmp_path / "out.png"), 4, 3)    # exposure 1: fine


def test_povray_that_cannot_run(tmp_path):
    with pytest.raises(UserError, match="cannot run POV-Ray"):
        povray.render(str(tmp_path / "missing"), scene_file(tmp_path), pov.Plan(1, True),
                      str(tmp_path / "o.png"), 4, 3)


def read_pfm(path):
    """RGB floats of a PFM, top row first."""
    with open(path, "rb") as f:
        data = f.read()
    parts, pos = [], 0
    while len(parts) < 3:
        end = data.index(b"\n", pos)
        parts.append(data[pos:end].decode())
        pos = end + 1
    w, h = map(int, parts[1].split())
    fmt = ("<" if float(parts[2]) < 0 else ">") + f"{3 * w * h}f"
    values = struct.unpack(fmt, data[pos:pos + 12 * w * h])
    rows = [values[3 * w * j:3 * w * (j + 1)] for j in range(h)]
    return w, h, [v for row in reversed(rows) for v in row]              # PFM rows go bottom up


def test_real_povray_renders_the_scene_like_facets_reference(tmp_path, facet, povray_exe):
    """three_meshes (function pigments, 3 passes) by POV-Ray at 40x30 against facet's
    reference render: within 2e-3 · max(1, |ref|) on all but 0.1 % of the samples."""
    with open(example("scenes", "three_meshes.json"), encoding="utf-8") as f:
        data = json.load(f)
    pov_path = str(tmp_path / "three.pov")
    plan = pov.generate_scene(facet, data, "three", pov_path)
    w, h = 40, 30
    exposure = 0.25                              # the reference goes above 1; the PNG clips at 1
    assert povray.render(povray_exe, pov_path, plan, str(tmp_path / "three.png"), w, h, exposure) == plan.passes == 3
    _, _, _, got = read_png(str(tmp_path / "three.png"))
    subprocess.run([facet, "render", "--scene", example("scenes", "three_meshes.json"), "-r", "reference",
                    "--size", f"{w}x{h}", "-o", str(tmp_path / "ref.pfm")], check=True, stdout=subprocess.DEVNULL)
    _, _, ref = read_pfm(str(tmp_path / "ref.pfm"))
    assert max(ref) * exposure < 1.0
    close = sum(abs(g / 65535.0 - r * exposure) <= 2e-3 * max(1.0, r * exposure) + 1.0 / 65535
                for g, r in zip(got, ref))
    lit = sum(r > 0 for r in ref)
    assert lit > len(ref) // 4, "the reference shows the scene"
    # Measured: all 3600 agree; POV-Ray's one run (light_group copies) misses 6, which this catches.
    assert len(ref) - close <= len(ref) // 1000, f"only {close} of {len(ref)} samples agree"
