#!/usr/bin/env bash
# Partitioning throughput and peak memory on a generated mesh.
#   bench/partition.sh [TRIANGLES] [SCRATCH_DIR]
# Generates a bumpy torus of TRIANGLES (default 50 million) as binary PLY in SCRATCH_DIR
# (default a new directory under /tmp, removed afterwards), then times `atp build` on it.
# Prints the generator's and the builder's figures; the builder's last lines carry the
# throughput (triangles/s) and the peak resident memory of the whole run.
set -euo pipefail
cd "$(dirname "$0")/.."
triangles=${1:-50000000}
scratch=${2:-$(mktemp -d /tmp/atp-bench.XXXXXX)}
cleanup() { rm -f "$scratch/bench.ply" "$scratch/bench.atp"; [ -n "${2:-}" ] || rmdir "$scratch" 2>/dev/null || true; }
trap cleanup EXIT

[ -x build/bin/atp ] || bash scripts/build.sh
source bench/common.sh
machine
build/bin/atp generate -n "$triangles" -o "$scratch/bench.ply"
ls -l "$scratch/bench.ply" | awk '{printf "input: %.0f MiB binary PLY\n", $5/1048576}'
# Warm the page cache once so the figure measures the build, not the disk.
cat "$scratch/bench.ply" > /dev/null
build/bin/atp build "$scratch/bench.ply" -o "$scratch/bench.atp" --scratch "$scratch" --quiet
