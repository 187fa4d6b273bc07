#!/usr/bin/env bash
# Partitioning throughput and peak memory on a generated mesh.
#   bench/partition.sh [TRIANGLES] [SCRATCH_DIR]
# Generates a bumpy torus of TRIANGLES (default 50 million) as binary PLY in SCRATCH_DIR
# (default a new directory under /tmp, removed afterwards).
# Prints the generator's figures, then the partitioning phase alone as `atp build` runs it
# (atp-bench-partition: the first pass over the faces, the streaming into buckets, throughput)
# and its peak resident memory.
set -euo pipefail
cd "$(dirname "$0")/.."
triangles=${1:-50000000}
source bench/common.sh
scratch_dir "${2:-}"
cleanup() { remove_scratch "$scratch/bench.ply"; }
trap cleanup EXIT

[ -x build/bin/atp ] && [ -x build/bin/atp-bench-partition ] || bash scripts/build.sh
machine
build/bin/atp generate -n "$triangles" -o "$scratch/bench.ply"
ls -l "$scratch/bench.ply" | awk '{printf "input: %.0f MiB binary PLY\n", $5/1048576}'
# Warm the page cache once so the figure measures the partitioning, not the disk.
cat "$scratch/bench.ply" > /dev/null
/usr/bin/time -f "peak resident memory: %M KiB" build/bin/atp-bench-partition "$scratch/bench.ply" "$scratch"
