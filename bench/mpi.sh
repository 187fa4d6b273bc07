#!/usr/bin/env bash
# Distributed construction figures: atp build on threads (1 and 2) and with --mpi and 1, 2, 3
# workers (mpirun -np 2..4 on this machine), each model checked byte-identical to the threaded
# one; wall time, construction (simplify) time, speed-up, CPU time of all processes (what MPI
# costs in work, whatever else runs on the machine), coordinator and per-worker peak memory.
#   bench/mpi.sh brain|TRIANGLES|MESH.ply [SCRATCH_DIR]
# Inputs as in bench/build.sh. The load average is printed before every run: on a shared
# machine, other work shows up in the times.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-brain}
source bench/common.sh
scratch_dir "${2:-}" atp-bench-mpi
input_path "$what" "$scratch"
cleanup() {
  [ "$input" = "$what" ] || rm -f "$input"
  remove_scratch "$scratch"/threads-*.atp "$scratch"/mpi-*.atp "$scratch"/run.log "$scratch"/time.log
}
trap cleanup EXIT

machine ", $(mpirun --version | head -1)"
make_input "$what"
cat "$input" >/dev/null

# run NAME COMMAND...: one build, its figures on one line.
baseline=""
run() {
  local name=$1
  shift
  local load
  load=$(cut -d' ' -f1 /proc/loadavg)
  # mpirun waits for its ranks, so its children's CPU time is theirs.
  /usr/bin/time -f "%U %S" -o "$scratch/time.log" "$@" >"$scratch/run.log" 2>&1 ||
    { cat "$scratch/run.log"; exit 1; }
  local wall simplify workers coordinator cpu
  cpu=$(awk '{ print $1 + $2 }' "$scratch/time.log")
  wall=$(sed -nE 's/^done: .*\(([0-9.]+)s\).*/\1/p' "$scratch/run.log")
  simplify=$(sed -nE 's/^simplify: .*, ([0-9.]+)s$/\1/p' "$scratch/run.log")
  coordinator=$(sed -nE 's/^done: .*peak memory ([0-9]+) MiB/\1/p' "$scratch/run.log")
  workers=$(sed -nE 's/^mpi: (.*)$/; \1/p' "$scratch/run.log")
  [ -n "$baseline" ] || baseline=$wall
  awk -v n="$name" -v w="$wall" -v s="$simplify" -v b="$baseline" -v c="$coordinator" \
    -v l="$load" -v k="$workers" -v u="$cpu" 'BEGIN {
    printf "%-16s %7.1f s wall (simplify %6.1f s), speed-up %.2f, %7.1f s CPU, peak %s MiB (load before %s)%s\n",
      n, w, s, b / w, u, c, l, k }'
}

options=(--quiet --scratch "$scratch")
run "threads 1" build/bin/atp build "$input" -o "$scratch/threads-1.atp" -j 1 "${options[@]}"
run "threads 2" build/bin/atp build "$input" -o "$scratch/threads-2.atp" -j 2 "${options[@]}"
cmp "$scratch/threads-1.atp" "$scratch/threads-2.atp"
for workers in 1 2 3; do
  run "mpi $workers worker(s)" mpirun --allow-run-as-root --oversubscribe -np $((workers + 1)) \
    build/bin/atp build "$input" -o "$scratch/mpi-$workers.atp" --mpi "${options[@]}"
  cmp "$scratch/threads-1.atp" "$scratch/mpi-$workers.atp"
  rm -f "$scratch/mpi-$workers.atp"
done
echo "every MPI model is byte-identical to the threaded one"
