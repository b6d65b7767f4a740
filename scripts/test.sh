#!/usr/bin/env bash
# Installs what is missing, builds tetrender (Release, warnings are errors) and runs every test.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   ASan + UBSan build in build-sanitize/
#   scripts/test.sh --fuzz-smoke the libFuzzer targets (clang, ASan + UBSan) in build-fuzz/,
#                                each run for 5 s on its seeds (docs/fuzzing.md)
# Extra arguments after -- go to ctest (e.g. -- -L unit).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/packages.sh

sanitize=0
fuzz=0
ctest_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --sanitize) sanitize=1 ;;
    --fuzz-smoke) fuzz=1 ;;
    --) shift; ctest_args=("$@"); break ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "test.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done

if [ $fuzz -eq 1 ]; then
  TETRENDER_PACKAGES+=(clang libclang-rt-14-dev libfuzzer-14-dev)
else
  TETRENDER_PACKAGES+=("${TETRENDER_MPI_PACKAGES[@]}")
fi
ensure_packages
jobs=$(nproc)
if [ $fuzz -eq 1 ]; then
  build=build-fuzz
  # Only the libraries the targets need, -O1 -g1, without CGAL (no target reaches it): the
  # smoke run checks that every target builds and survives its seeds, not their coverage.
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
        -DCMAKE_CXX_COMPILER=clang++ -DTETRENDER_FUZZ=ON -DTETRENDER_WITH_CGAL=OFF \
        -DTETRENDER_BUILD_TESTS=OFF -DTETRENDER_BUILD_BENCH=OFF -DTETRENDER_BUILD_APPS=OFF \
        -DTETRENDER_BUILD_VIEWER=OFF -DTETRENDER_PYTHON=OFF -DTETRENDER_WITH_MPI=OFF \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  cmake --build "$build" -j "$jobs"
  ctest --test-dir "$build" --output-on-failure -L fuzz "${ctest_args[@]}"
  exit 0
fi
if [ $sanitize -eq 1 ]; then
  build=build-sanitize
  # -O1 -g1 (line tables, enough for the sanitizers' stack traces): compiles in about half the
  # time of -O2 -g (measured on a CGAL and a VTK translation unit under ASan).
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETRENDER_SANITIZE=ON \
        -DTETRENDER_WITH_MPI=ON -DTETRENDER_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  # VTK's own singletons are never freed: do not call them leaks of ours.
  export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
  # intercept_tls_get_addr=0: GCC 12's runtime takes a dynamic TLS block that happens to start 16
  # bytes into a page for a glibc-2.19 header, reads a bogus range from it ("DTLS 17 at
  # 0x1b68-0x1800002c6a" with verbosity=1) and LeakSanitizer's tracer dies at exit ("Tracer caught
  # signal 11"); it hit tetrender-view (Mesa's TLS) in 5 of 6 runs, 0 of 8 with this.
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
else
  build=build
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DTETRENDER_WITH_MPI=ON
fi
# mpirun as root (CI) needs these; ranks beyond the cores need --oversubscribe (the tests pass
# it); in containers OpenMPI's shared-memory single copy (CMA) may be refused.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "${ctest_args[@]}"
