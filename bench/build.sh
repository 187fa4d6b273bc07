#!/usr/bin/env bash
# End-to-end construction figures: throughput, peak memory, temporary disk, bytes per triangle.
#   bench/build.sh brain|TRIANGLES|MESH.ply [SCRATCH_DIR] [-- ATP_BUILD_OPTION...]
# "brain": the MRI isosurface of ch2better.nii.gz (mricron-data) at 60, resampled 2x (9.1M
# triangles). A number: a generated bumpy torus of at least that many triangles. A file: that
# mesh.
# Generated inputs go to SCRATCH_DIR (default a new directory under /tmp, removed afterwards).
# Options after "--" go to `atp build` (e.g. -- --fast-cache-order).
# The page cache is warmed, then `atp build` runs while the file system's used space is sampled,
# so the temporary disk figure is measured, not estimated (the scratch files are unlinked and
# invisible to du).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/common.sh
what_scratch_options "$@"
scratch_dir "$given_scratch"
input_path "$what" "$scratch"
cleanup() {
  [ "$input" = "$what" ] || rm -f "$input"
  remove_scratch "$scratch/model.atp" "$scratch/df.log"
}
trap cleanup EXIT

machine
make_input "$what"
input_bytes=$(stat -c %s "$input")
echo "input: $((input_bytes / 1048576)) MiB binary PLY"
cat "$input" > /dev/null

used() { df -B1 --output=used "$scratch" | tail -1; }
base=$(used)
( while sleep 0.5; do used; done ) > "$scratch/df.log" &
sampler=$!
/usr/bin/time -f "time: %e s wall, %U s user, peak resident %M KiB" \
  build/bin/atp build "$input" -o "$scratch/model.atp" --scratch "$scratch" --quiet "${options[@]}"
kill "$sampler"
peak=$(sort -n "$scratch/df.log" | tail -1)
model_bytes=$(stat -c %s "$scratch/model.atp")
awk -v peak="$peak" -v base="$base" -v input="$input_bytes" -v model="$model_bytes" 'BEGIN {
  extra = peak - base
  printf "disk: peak %.0f MiB above the input (temporary files and the model), %.2fx the input\n", extra / 1048576, extra / input
  printf "model: %.1f MiB\n", model / 1048576 }'
