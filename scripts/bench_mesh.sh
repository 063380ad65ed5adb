#!/usr/bin/env bash
# POV-Ray on meshes of 2 k … 2 M triangles (tests/bench/README.md, docs/povray-meshes.md):
# for the native route (Lambert + Blinn–Phong), an isotropic (Oren–Nayar + GGX) and an
# anisotropic (Ward) material on function pigments (and the isotropic one through
# --pov-route fast's slope tables), the times of facet import-gltf,
# facet generate and POV-Ray (parse, trace at 640×480), the files' sizes, peak memory,
# the ratio to the native route and the growth exponents.
#
#   scripts/bench_mesh.sh [--sizes 2k,8k,32k,128k,512k,2M] [--materials native,isotropic,anisotropic,isotropic-fast]
#
# Needs the build (build/bin/facet_mesh_bench). Writes out/mesh_bench/ (the scenes) and
# docs/mesh_bench.md with its plots docs/mesh_bench_parse.svg and docs/mesh_bench_memory.svg.
# The 2 M-triangle size takes about 10 minutes and 4 GB of disk on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build/bin/facet_mesh_bench --out out/mesh_bench --markdown docs/mesh_bench.md --plot docs/mesh_bench.svg "$@"
