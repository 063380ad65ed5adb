#!/usr/bin/env bash
# facet's whole test suite, what CI runs (.ci/run). Three stages, each its own
# build tree under the repo (ignored by git, kept between runs):
#
#   main      build/        every test (CTest), the release build users get
#   sanitize  build-asan/   the suite again, built with AddressSanitizer and
#                           UndefinedBehaviorSanitizer, less the tests labelled
#                           `external` (their time is an outside program's, and
#                           the facet code they call runs here in other tests;
#                           tests/CMakeLists.txt lists them and says why)
#   fuzz      build-fuzz/   the libFuzzer targets (clang), a bounded run each
#                           from the seed corpus (tests/fuzz)
#
#   scripts/test.sh                   all three stages
#   scripts/test.sh -L pov            CTest arguments go to every stage
#   FACET_TEST_STAGES=main scripts/test.sh   some stages only (local work; CI runs all)
#
# It first makes sure everything is installed and built (scripts/setup.sh --no-run).
set -euo pipefail
cd "$(dirname "$0")/.."
stages=${FACET_TEST_STAGES:-main sanitize fuzz}
jobs=$(nproc)

# The sanitizer builds: -O1, as AddressSanitizer's own documentation advises, and
# line tables only (-g1), which is all a sanitizer's stack trace prints (function,
# file:line). Measured on this suite: the build in 4.5 min instead of 11 with
# -O2 -g, and the tests no slower (391 s against 436 s).
sanitizer_flags="-O1 -g1 -DNDEBUG"

say() { printf '\033[1m==> %s\033[0m\n' "$*"; }

# configure DIR ARGS…, then build it; the log is shown only when it fails.
build_tree() {
  local dir=$1
  shift
  mkdir -p "$dir"
  cmake -S . -B "$dir" "$@" > "$dir/build.log" 2>&1 || { cat "$dir/build.log"; exit 1; }
  cmake --build "$dir" -j"$jobs" >> "$dir/build.log" 2>&1 || { tail -50 "$dir/build.log"; exit 1; }
}

scripts/setup.sh --no-run

for stage in $stages; do
  case $stage in
    main)
      say "Stage main: the whole suite (build/)"
      (cd build && ctest --output-on-failure -j"$jobs" "$@")
      ;;
    sanitize)
      say "Stage sanitize: the suite under AddressSanitizer and UndefinedBehaviorSanitizer, less label external (build-asan/)"
      build_tree build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$sanitizer_flags" \
        -DFACET_SANITIZE=ON -DFACET_WERROR=ON \
        -DFACET_PYTHON="$PWD/.venv/bin/python"
      # Leak checking included: facet's processes end with every allocation freed
      # or still reachable (gl_renderer.cpp pins Mesa's driver so its own stays reachable).
      # intercept_tls_get_addr=0: GCC 12's sanitizer runtime takes some dynamic TLS
      # blocks of glibc ≥ 2.25 for glibc 2.19's layout and reads a bogus range from
      # them, and LeakSanitizer's tracer then dies at exit (google/sanitizers#1322;
      # it depends on where Mesa's TLS lands, so a change of layout anywhere shows it).
      # Without the interceptor those blocks are not scanned as roots, which can only
      # add leak reports, never hide one.
      (cd build-asan &&
        ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:intercept_tls_get_addr=0 \
        UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        ctest --output-on-failure -j"$jobs" -LE external "$@")
      ;;
    fuzz)
      say "Stage fuzz: libFuzzer targets, bounded runs (build-fuzz/)"
      build_tree build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$sanitizer_flags" -DFACET_FUZZ=ON \
        -DFACET_WERROR=ON
      (cd build-fuzz && ctest --output-on-failure -j"$jobs" "$@")
      ;;
    *)
      echo "error: FACET_TEST_STAGES: unknown stage \"$stage\"; allowed: main, sanitize, fuzz" >&2
      exit 2
      ;;
  esac
done
