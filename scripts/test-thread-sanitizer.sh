#!/usr/bin/env bash
# The threaded parts (the input's two-thread passes and partitioning; construction's ordered
# pipeline, a threaded build and jobs loaded on their threads; rendering's
# background decoding, prefetching and the mapper that drives them) under ThreadSanitizer, in
# build-tsan/. Fails on any report.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=build-tsan
if [ ! -f "$build_dir/build.ninja" ]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DATP_SANITIZE=thread
fi
cmake --build "$build_dir" -j "$(nproc)" --target TestParallel TestTriangleSources TestPartitioner TestConstruction TestPatchJob TestRenderingCore TestMapper
export TSAN_OPTIONS="halt_on_error=1 abort_on_error=1 suppressions=$PWD/Testing/tsan.supp"
"$build_dir/tests/TestParallel"
# Bounds on the process's peak memory mean nothing here: ThreadSanitizer's shadow memory
# multiplies every page a test reads (opening 12M vertices reads 96 MiB of boundary sketch).
"$build_dir/tests/TestTriangleSources" --gtest_filter='-*OpeningLetsGoOfTheVertexPagesItHasRead:*OpeningAnStlHoldsLittleOfIt'
"$build_dir/tests/TestPartitioner" --gtest_filter='*Stream*'
"$build_dir/tests/TestConstruction" --gtest_filter='*ThreadCount*'
"$build_dir/tests/TestPatchJob" --gtest_filter='*Loaded*'
"$build_dir/tests/TestRenderingCore"
bash scripts/headless.sh "$build_dir/tests/TestMapper"
echo "ThreadSanitizer: no reports"
