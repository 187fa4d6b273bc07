#!/usr/bin/env bash
# Fuzzes the .atp reader, the patch decoder and the mesh readers with libFuzzer (clang, with
# AddressSanitizer and UndefinedBehaviorSanitizer) for SECONDS each (default 300), in build-fuzz/.
# Inputs that grow coverage collect in build-fuzz/corpus/TARGET; a crash leaves its input in
# build-fuzz/crashes/TARGET/ and stops with a non-zero exit: keep it under
# Testing/Fuzz/regressions/TARGET/ once fixed, so CTest replays it ever after.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: ModelFile PatchDecoder MeshReaders)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(ModelFile PatchDecoder MeshReaders)
build_dir=build-fuzz
if [ ! -f "$build_dir/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DATP_FUZZ=ON -DATP_SANITIZE=address,undefined
fi
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]/#/Fuzz}"
# Leaks are reported by the sanitizer suite; here a leak would only end the run early.
export ASAN_OPTIONS=detect_leaks=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for target in "${targets[@]}"; do
  corpus="$build_dir/corpus/$target"
  crashes="$build_dir/crashes/$target"
  mkdir -p "$corpus" "$crashes"
  seeds=(Testing/Fuzz/corpus/"$target")
  [ -d Testing/Fuzz/regressions/"$target" ] && seeds+=(Testing/Fuzz/regressions/"$target")
  echo "== $target: ${seconds}s"
  "$build_dir/fuzz/Fuzz$target" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
    -max_len=65536 -rss_limit_mb=2048 -timeout=10 -artifact_prefix="$crashes/" \
    -print_final_stats=1 2>&1 | grep -E "^stat::number_of_executed_units|^stat::peak_rss|Done|ERROR|SUMMARY|==[0-9]+==" || true
  if [ -n "$(ls -A "$crashes")" ]; then
    echo "fuzz.sh: $target found crashing inputs in $crashes" >&2
    exit 1
  fi
done
