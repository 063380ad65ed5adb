#!/usr/bin/env bash
# facet's one set-up command: Debian packages, the Python environment (.venv),
# the build (build/), then the main job on the bundled examples.
#
#   scripts/setup.sh            everything, then the main job
#   scripts/setup.sh --no-run   everything but the main job (scripts/test.sh uses this)
#
# Each step is skipped when already done, so running it again is cheap.
set -euo pipefail
cd "$(dirname "$0")/.."
run_main=1
[ "${1:-}" = "--no-run" ] && run_main=0

say() { printf '\033[1m==> %s\033[0m\n' "$*"; }

# ---- Debian packages
packages=(
  build-essential cmake pkg-config git
  nlohmann-json3-dev libfmt-dev libcli11-dev libtinygltf-dev libstb-dev googletest libgtest-dev libbenchmark-dev
  glslang-tools spirv-tools spirv-cross libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  povray blender xvfb python3 python3-venv python3-pip chromium valgrind fonts-dejavu-core
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "Installing Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi

# ---- Python environment: bpy 4.5 needs CPython 3.11
python=${FACET_PYTHON_BASE:-python3}
if [ ! -x .venv/bin/python ] || ! cmp -s requirements.txt .venv/requirements.txt; then
  version=$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')
  if [ "$version" != "3.11" ]; then
    echo "error: bpy 4.5 needs Python 3.11; $python is $version (set FACET_PYTHON_BASE)" >&2
    exit 1
  fi
  say "Making the Python environment .venv (bpy 4.5 is about 370 MB)"
  "$python" -m venv .venv
  .venv/bin/pip install --quiet --upgrade pip
  .venv/bin/pip install --quiet -r requirements.txt
  cp requirements.txt .venv/requirements.txt
fi

# ---- Build
say "Building (build/bin/facet)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFACET_WERROR=ON -DFACET_PYTHON="$PWD/.venv/bin/python" > build.log 2>&1 \
  || { cat build.log; exit 1; }
cmake --build build -j"$(nproc)" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
rm -f build.log

[ $run_main -eq 1 ] || exit 0

# ---- The main job: every example for every target, then the whole catalog through
# every renderer, compared pixel by pixel with the reference (out/validate/report.html)
say "Generating every example for every target into out/examples"
mkdir -p out/examples
for m in examples/materials/*.json examples/layered/*.json; do
  name=$(basename "$m" .json)
  for t in glsl glsl450 essl hlsl wgsl osl pov; do
    build/bin/facet generate "$m" --target "$t" -o "out/examples/$name.$t"
  done
done
say "facet validate: the example catalog through OpenGL, Vulkan (GLSL 4.50, HLSL), WebGL2, wgpu (WGSL), Cycles (OSL) and POV-Ray against the C++ reference"
build/bin/facet validate --out out/validate
