#!/usr/bin/env bash
# End-to-end construction figures: throughput, peak memory, temporary disk, bytes per triangle.
#   bench/build.sh brain|TRIANGLES [SCRATCH_DIR]
# "brain": the MRI isosurface of ch2better.nii.gz (mricron-data) at 60, resampled 2x (9.2M
# triangles). A number: a generated bumpy torus of that many triangles (e.g. 100000000).
# The input is written to SCRATCH_DIR (default a new directory under /tmp, removed afterwards),
# the page cache warmed, then `atp build` runs while the file system's used space is sampled, so
# the temporary disk figure is measured, not estimated (the scratch files are unlinked and
# invisible to du).
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-brain}
scratch=${2:-$(mktemp -d /tmp/atp-bench.XXXXXX)}
cleanup() {
  rm -f "$scratch/input.ply" "$scratch/model.atp" "$scratch/df.log"
  [ -n "${2:-}" ] || rmdir "$scratch" 2>/dev/null || true
}
trap cleanup EXIT

[ -x build/bin/atp ] && [ -x build/bin/atp-bench-brain-surface ] || bash scripts/build.sh
echo "machine: $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
if [ "$what" = brain ]; then
  build/bin/atp-bench-brain-surface "$scratch/input.ply" 2 60
else
  build/bin/atp generate -n "$what" -o "$scratch/input.ply"
fi
input_bytes=$(stat -c %s "$scratch/input.ply")
echo "input: $((input_bytes / 1048576)) MiB binary PLY"
cat "$scratch/input.ply" > /dev/null

used() { df -B1 --output=used "$scratch" | tail -1; }
base=$(used)
( while sleep 0.5; do used; done ) > "$scratch/df.log" &
sampler=$!
build/bin/atp build "$scratch/input.ply" -o "$scratch/model.atp" --scratch "$scratch" --quiet
kill "$sampler"
peak=$(sort -n "$scratch/df.log" | tail -1)
model_bytes=$(stat -c %s "$scratch/model.atp")
awk -v peak="$peak" -v base="$base" -v input="$input_bytes" -v model="$model_bytes" 'BEGIN {
  extra = peak - base
  printf "disk: peak %.0f MiB above the input (temporary files and the model), %.2fx the input\n", extra / 1048576, extra / input
  printf "model: %.1f MiB\n", model / 1048576 }'
