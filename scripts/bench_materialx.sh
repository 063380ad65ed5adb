#!/usr/bin/env bash
# MaterialX's ShaderGen against facet for the BRDFs both have (tests/bench/README.md):
# generation time per material, SPIR-V instructions, llvmpipe instructions per pixel
# under callgrind, and both renders against facet's C++ reference, side by side.
#
#   scripts/bench_materialx.sh [--repeats N] [--no-callgrind]
#
# Needs the build (build/bin/facet_materialx_bench) and .venv with pip materialx
# (requirements.txt); writes out/bench_materialx/ (the shaders, the job, the table).
set -euo pipefail
cd "$(dirname "$0")/.."
python=${FACET_PYTHON:-.venv/bin/python}
out=out/bench_materialx
mkdir -p "$out"
"$python" tests/bench/materialx_bench.py build/bin/facet_materialx_bench "$out" "$@" | tee "$out/table.txt"
