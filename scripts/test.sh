#!/usr/bin/env bash
# facet's whole test suite: makes sure everything is installed and built
# (scripts/setup.sh --no-run), then runs every test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --no-run
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
