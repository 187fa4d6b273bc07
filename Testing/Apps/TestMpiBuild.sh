#!/usr/bin/env bash
# atp build --mpi under mpirun on this machine (1 coordinator, 2 workers): the model is
# byte-identical to the single-process build; a worker that fails or dies mid-build ends the run
# with a non-zero exit code and leaves no model (an existing one untouched).
#   TestMpiBuild.sh ATP_BINARY DATA_DIR MPIEXEC
set -u
atp=$1
data=$2
mpiexec=$3
source "$(dirname "$0")/expect.sh"
mpi() {
  "$mpiexec" --allow-run-as-root --oversubscribe -np 3 "$@"
}
options=(--leaf-capacity 1000 --patch-budget 500 --quiet)

"$atp" build "$data/bumpy-torus.ply" -o "$work/single.atp" "${options[@]}" -j 1 >/dev/null ||
  fail "single-process build"
out=$(mpi "$atp" build "$data/bumpy-torus.ply" -o "$work/mpi.atp" "${options[@]}" --mpi 2>&1) ||
  fail "mpi build: $out"
grep -qE "mpi: 2 workers, jobs per worker [0-9]+/[0-9]+, [0-9]+ MiB shipped to workers and [0-9]+ MiB back, coordinator CPU [0-9.]+s, peak memory per worker [0-9]+ MiB" <<<"$out" ||
  fail "no worker summary in: $out"
cmp -s "$work/single.atp" "$work/mpi.atp" || fail "the MPI model differs from the single-process one"
# The workers order triangles as the coordinator was told.
"$atp" build "$data/bumpy-torus.ply" -o "$work/single-fast.atp" "${options[@]}" --fast-cache-order -j 1 \
  >/dev/null || fail "single-process build, fast cache order"
out=$(mpi "$atp" build "$data/bumpy-torus.ply" -o "$work/mpi-fast.atp" "${options[@]}" --fast-cache-order \
  --mpi 2>&1) || fail "mpi build, fast cache order: $out"
cmp -s "$work/single-fast.atp" "$work/mpi-fast.atp" ||
  fail "the MPI model differs from the single-process one (fast cache order)"
rm -f "$work/single-fast.atp" "$work/mpi-fast.atp"

# Faults injected in the workers (ATP_MPI_TEST_FAULT, see Apps/atpMpiBuild.h).
echo "previous model" >"$work/old.atp"
for fault in throw:4 kill:4; do
  out=$(ATP_MPI_TEST_FAULT=$fault mpi -x ATP_MPI_TEST_FAULT \
    "$atp" build "$data/bumpy-torus.ply" -o "$work/old.atp" "${options[@]}" --mpi 2>&1)
  status=$?
  [ "$status" -ne 0 ] || fail "$fault: exit code 0"
  [ "$(cat "$work/old.atp")" = "previous model" ] || fail "$fault: the existing model was touched"
  out=$(ATP_MPI_TEST_FAULT=$fault mpi -x ATP_MPI_TEST_FAULT \
    "$atp" build "$data/bumpy-torus.ply" -o "$work/new.atp" "${options[@]}" --mpi 2>&1)
  [ $? -ne 0 ] || fail "$fault: exit code 0"
  [ ! -e "$work/new.atp" ] || fail "$fault: a model was left behind"
  case $fault in
  throw:*) grep -q "atp build: error: worker [12] failed on job [0-9]*: injected fault" <<<"$out" ||
    fail "$fault: no clear error in: $out" ;;
  kill:*) grep -q "exited on signal 9" <<<"$out" || fail "$fault: mpirun did not name the dead worker: $out" ;;
  esac
done
[ -z "$(ls "$work" | grep -v -e '^single.atp$' -e '^mpi.atp$' -e '^old.atp$')" ] ||
  fail "files left behind: $(ls "$work")"

# Without workers: one clear line.
out=$("$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --mpi 2>&1)
[ $? -eq 1 ] && grep -q "needs at least 2 processes" <<<"$out" || fail "no workers: $out"

echo "$failures failed"
[ "$failures" -eq 0 ]
