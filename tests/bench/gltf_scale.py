"""How reading big glTF meshes scales: time and peak memory of `facet import-gltf` and of
`facet generate --target glsl --scene` on the referencing scene it writes, for subdivided
icospheres (make_icosphere_glb.py) of growing size, and the exponent b of t ∝ n^b.

    python3 tests/bench/gltf_scale.py build/bin/facet [--sizes 32000,128000,512000,2000000]
                                      [--workdir out/gltf_scale] [--repeats 3] [--check]

Each figure is the least of --repeats runs under /usr/bin/time (-f "%e %M": seconds and
peak resident KiB), printed in MB (10⁶ bytes). The memory exponent is also given for the
peak less facet's own (the peak of `facet generate` without a scene). --check exits 1
unless both commands' peak memory is within 4 × the GLB's size + 300 MB at every size.
Standard library only.
"""
import argparse
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def timed(cmd):
    """(seconds, peak kB) of one run of `cmd`."""
    proc = subprocess.run(["/usr/bin/time", "-f", "%e %M"] + cmd, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit(f"failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
    seconds, kb = proc.stderr.strip().splitlines()[-1].split()
    return float(seconds), int(kb)


def best(cmd, repeats):
    runs = [timed(cmd) for _ in range(repeats)]
    return min(r[0] for r in runs), min(r[1] for r in runs)


def slope(xs, ys):
    """The least-squares slope of log y against log x (the exponent)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(max(y, 1e-3)) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("facet")
    ap.add_argument("--sizes", default="32000,128000,512000,2000000")
    ap.add_argument("--workdir", default=os.path.join(ROOT, "out", "gltf_scale"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    material = os.path.join(ROOT, "examples", "materials", "lambert.json")
    rows, failures = [], 0
    base = best([a.facet, "generate", material, "--target", "glsl", "-o", os.path.join(a.workdir, "none.glsl")],
                a.repeats)[1] * 1024 / 1e6
    for n in [int(s) for s in a.sizes.split(",")]:
        glb = os.path.join(a.workdir, f"icosphere_{n}.glb")
        scene = os.path.join(a.workdir, f"icosphere_{n}.json")
        made = subprocess.run([sys.executable, os.path.join(HERE, "make_icosphere_glb.py"), str(n), glb], check=True,
                              stderr=subprocess.PIPE, text=True)
        held = int(made.stderr.split(": ")[1].split()[0])  # the triangles it holds: 20 k² for a whole k
        imp = best([a.facet, "import-gltf", glb, "-o", scene], a.repeats)
        gen = best([a.facet, "generate", material, "--target", "glsl", "--scene", scene, "-o",
                    os.path.join(a.workdir, f"icosphere_{n}.glsl")], a.repeats)
        size = os.path.getsize(glb)
        imp, gen = (imp[0], imp[1] * 1024 / 1e6), (gen[0], gen[1] * 1024 / 1e6)  # MB
        bound = 4 * size / 1e6 + 300
        ok = imp[1] <= bound and gen[1] <= bound
        failures += not ok
        rows.append((held, size, os.path.getsize(scene), imp, gen, bound, ok))
    print("| triangles | GLB MB | scene file B | import-gltf s | import-gltf peak MB | generate s | generate peak MB "
          "| bound 4 × GLB + 300 MB | within |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n, size, scene_size, imp, gen, bound, ok in rows:
        print(f"| {n:,} | {size / 1e6:.1f} | {scene_size:,} | {imp[0]:.2f} | {imp[1]:.0f} | {gen[0]:.2f} | "
              f"{gen[1]:.0f} | {bound:.0f} | {'yes' if ok else 'NO'} |")
    print(f"\nfacet's own peak (generate without a scene): {base:.0f} MB")
    if len(rows) > 1:
        ns = [r[0] for r in rows]
        print(f"exponent b (least squares of log against log n): import-gltf time {slope(ns, [r[3][0] for r in rows]):.2f}, "
              f"memory {slope(ns, [r[3][1] for r in rows]):.2f} (above facet's own: "
              f"{slope(ns, [r[3][1] - base for r in rows]):.2f}); generate time {slope(ns, [r[4][0] for r in rows]):.2f}, "
              f"memory {slope(ns, [r[4][1] for r in rows]):.2f} (above facet's own: {slope(ns, [r[4][1] - base for r in rows]):.2f})")
        last, prev = rows[-1], rows[-2]
        k = math.log(last[0] / prev[0])
        print(f"between the two largest sizes: import-gltf time {math.log(last[3][0] / max(prev[3][0], 1e-3)) / k:.2f}, "
              f"memory {math.log(last[3][1] / prev[3][1]) / k:.2f}; generate time "
              f"{math.log(last[4][0] / max(prev[4][0], 1e-3)) / k:.2f}, memory {math.log(last[4][1] / prev[4][1]) / k:.2f}")
    return 1 if a.check and failures else 0


if __name__ == "__main__":
    sys.exit(main())
