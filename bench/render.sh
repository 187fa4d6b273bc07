#!/usr/bin/env bash
# The rendering figures of `atp bench` on a large model: builds it, then flies the standard
# path (450 frames at 800x600, 1 px) with vtkATPMapper and with vtkPolyDataMapper on the full
# mesh, printing frame times, triangles/s, patches/frame, the CPU share of the frame, resident
# memory against the model's size, the speed-up and the image difference.
#   bench/render.sh brain|TRIANGLES|MESH.ply [SCRATCH_DIR] [-- ATP_BENCH_OPTION...]
# WHAT as for bench/build.sh. Generated inputs, the model and the per-frame CSV, plot and final
# frame go to SCRATCH_DIR (default a new directory under /tmp, removed afterwards; name one to
# keep them). The full-resolution flythrough is left out when the mesh would not fit in memory
# (about 4x its PLY size in VTK). Without a display, `atp bench` draws on an EGL device (a
# headless GPU); the summary's renderer line says what drew.
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/common.sh
what_scratch_options "$@"
scratch_dir "$given_scratch"
input_path "$what" "$scratch"
cleanup() {
  [ -z "$given_scratch" ] || return 0
  [ "$input" = "$what" ] || rm -f "$input"
  remove_scratch "$scratch"/{model.atp,frames.csv,plot.png,final.png}
}
trap cleanup EXIT

machine
make_input "$what"
[ -f "$scratch/model.atp" ] && [ "$scratch/model.atp" -nt "$input" ] ||
  build/bin/atp build "$input" -o "$scratch/model.atp" --scratch "$scratch" --quiet
input_bytes=$(stat -c %s "$input")
available=$(awk '/MemAvailable:/ {printf "%d\n", $2 * 1024}' /proc/meminfo)
compare=()
if [ $((input_bytes * 4)) -lt "$available" ]; then
  compare=(--compare-full "$input")
else
  echo "full-resolution flythrough left out: $((input_bytes >> 20)) MiB of mesh, $((available >> 20)) MiB of memory available"
fi
build/bin/atp bench "$scratch/model.atp" "${compare[@]}" --quiet --csv "$scratch/frames.csv" \
  --plot "$scratch/plot.png" --image "$scratch/final.png" "${options[@]}"
