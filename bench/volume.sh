#!/usr/bin/env bash
# The volume input's figures: a generated raw float32 volume of N^3 voxels (default 800:
# 1953 MiB), built by `atp build --iso` slab by slab; prints the contouring and build figures,
# wall time and the peak resident memory of the whole run, to compare with the volume's size.
#   bench/volume.sh [N] [SLAB] [SCRATCH_DIR]
# The volume goes to SCRATCH_DIR (default a new directory under /tmp, removed afterwards).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-800}
slab=${2:-64}
source bench/common.sh
scratch_dir "${3:-}"
cleanup() { remove_scratch "$scratch/volume.raw" "$scratch/model.atp"; }
trap cleanup EXIT

[ -x build/bin/atp ] && [ -x build/bin/atp-bench-volume ] || bash scripts/build.sh
machine
build/bin/atp-bench-volume "$scratch/volume.raw" "$n"
/usr/bin/time -f "time: %e s wall, %U s user, peak resident %M KiB" \
  build/bin/atp build "$scratch/volume.raw" --dims "$n,$n,$n" --type float32 --iso "$((n / 3))" \
  --slab "$slab" -o "$scratch/model.atp" --scratch "$scratch" --quiet
