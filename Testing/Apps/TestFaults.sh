#!/usr/bin/env bash
# Faults a build meets in the field: a full disk (a real one, a small tmpfs, in a private mount
# namespace that vanishes with the test), a build killed by SIGKILL at random moments,
# unreadable input. Each time: one clear line, a non-zero exit, no valid-looking output, the
# previous output untouched and nothing left behind.
#   TestFaults.sh ATP_BINARY DATA_DIR
set -u
# Root can mount a tmpfs of its own: re-run inside a private mount namespace.
if [ -z "${ATP_FAULTS_NAMESPACE:-}" ] && [ "$(id -u)" -eq 0 ] && unshare -m true 2>/dev/null; then
  ATP_FAULTS_NAMESPACE=1 exec unshare -m bash "$0" "$@"
fi
atp=$1
input=$2/bumpy-torus.ply
source "$(dirname "$0")/expect.sh"
chmod 755 "$work" # the unreadable-input check runs as nobody
mkdir "$work/out" "$work/scratch"

# A previous model that every failed build must leave as it was (other options than the builds
# below, so its bytes differ from theirs).
"$atp" build "$input" -o "$work/previous.atp" --leaf-capacity 20000 --quiet >/dev/null ||
  fail "the reference build failed"

# only_previous DIR: DIR holds model.atp, byte for byte the previous model, and nothing else.
only_previous() {
  cmp -s "$work/previous.atp" "$1/model.atp" || fail "$1/model.atp is no longer the previous model"
  [ "$(ls -A "$1")" = "model.atp" ] || fail "left behind in $1: $(ls -A "$1" | tr '\n' ' ')"
}

# --- A full disk, for the model and for the scratch files.
if [ -n "${ATP_FAULTS_NAMESPACE:-}" ]; then
  previous_kib=$(( $(stat -c %s "$work/previous.atp") / 1024 ))
  mkdir "$work/full"
  mount -t tmpfs -o size=$((previous_kib + 1024))k tmpfs "$work/full"
  cp "$work/previous.atp" "$work/full/model.atp"
  expect 1 "cannot write .*model.atp: No space left on device" -- \
    "$atp" build "$input" -o "$work/full/model.atp" --scratch "$work/scratch" --quiet
  only_previous "$work/full"
  umount "$work/full"

  mount -t tmpfs -o size=512k tmpfs "$work/full"
  cp "$work/previous.atp" "$work/out/model.atp"
  expect 1 "scratch .*No space left on device" -- \
    "$atp" build "$input" -o "$work/out/model.atp" --scratch "$work/full" --bucket-memory 1 --quiet
  only_previous "$work/out"
  [ -z "$(ls -A "$work/full")" ] || fail "scratch files left on the full disk: $(ls -A "$work/full")"
  # A mesh extracted onto it: the system's words, whatever VTK's writer says (its PLY writer
  # reports nothing, its STL writer an error code; its XML writer deletes the file and reports
  # the errno of what follows), and nothing left.
  for extension in ply stl vtp; do
    expect 1 "mesh.$extension: cannot write the mesh: No space left on device" -- \
      "$atp" extract "$work/previous.atp" -o "$work/full/mesh.$extension"
  done
  [ -z "$(ls -A "$work/full")" ] || fail "left on the full disk by extract: $(ls -A "$work/full")"
  umount "$work/full"
  # Pictures onto it: the file named, in the system's words (VTK's were an error code's name
  # and, from the viewer, a message that named no file).
  mount -t tmpfs -o size=16k tmpfs "$work/full"
  expect 1 "plot.png: cannot write the plot: No space left on device" -- \
    "$atp" bench "$work/previous.atp" --frames 3 --size 200x150 --plot "$work/full/plot.png"
  if [ -n "${DISPLAY:-}" ]; then
    expect 1 "shot.png: cannot write: No space left on device" -- \
      "$atp" view "$work/previous.atp" --size 640x480 --screenshot "$work/full/shot.png"
  fi
  [ -z "$(ls -A "$work/full")" ] || fail "left on the full disk by bench and view: $(ls -A "$work/full")"
  umount "$work/full"
  # A disk with room for the mesh, not for it twice: reading it back to check it takes its
  # scratch space where any scratch goes, not beside the output (that failed such extracts).
  for extension in ply stl; do
    "$atp" extract "$work/previous.atp" -o "$work/out/reference.$extension" >/dev/null ||
      fail "the reference extract failed"
    mount -t tmpfs -o size=$(( $(stat -c %s "$work/out/reference.$extension") / 1024 + 128 ))k tmpfs "$work/full"
    expect 0 "mesh.$extension" -- "$atp" extract "$work/previous.atp" -o "$work/full/mesh.$extension"
    cmp -s "$work/out/reference.$extension" "$work/full/mesh.$extension" ||
      fail "the mesh extracted onto a nearly full disk differs"
    umount "$work/full"
    rm "$work/out/reference.$extension"
  done

  # A read-only place is refused before the build, not when its model is renamed into place.
  mount -t tmpfs -o ro,size=64k tmpfs "$work/full"
  expect 1 "^atp build: error: .*model.atp: cannot write in its directory .*: Read-only file system" -- \
    "$atp" build "$input" -o "$work/full/model.atp" --quiet
  [ "$(wc -l <<<"$out")" -eq 1 ] || fail "build ran before refusing a read-only place: $out"
  umount "$work/full"
else
  echo "not root or no mount namespaces: a file size limit stands in for the full disk"
  cp "$work/previous.atp" "$work/out/model.atp"
  expect 1 "cannot write .*model.atp: File too large" -- bash -c \
    "ulimit -f $(( $(stat -c %s "$work/previous.atp") / 1024 + 64 )); exec '$atp' build '$input' -o '$work/out/model.atp' --scratch '$work/scratch' --quiet"
  only_previous "$work/out"
fi

# --- SIGKILL at moments spread over a build (tenths of its length, plus a random jitter): a
# build killed before its model is complete leaves the previous model; after (the rename, then
# exit and teardown) a valid new one. Never anything else, and no temporary file.
cp "$work/previous.atp" "$work/out/model.atp"
start=$(date +%s%N)
"$atp" build "$input" -o "$work/out/timed.atp" --bucket-memory 1 --scratch "$work/scratch" --quiet >/dev/null
build_ms=$(( ($(date +%s%N) - start) / 1000000 ))
rm -f "$work/out/timed.atp"
before_commit=0
for round in 0 1 2 3 4 5 6 7; do
  delay_ms=$(( build_ms * round / 10 + RANDOM % (build_ms / 10 + 1) ))
  "$atp" build "$input" -o "$work/out/model.atp" --bucket-memory 1 --scratch "$work/scratch" --quiet >/dev/null 2>&1 &
  pid=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -KILL "$pid" 2>/dev/null
  { wait "$pid"; } 2>/dev/null # no job-control line for the kill
  status=$?
  if [ "$status" -ne 137 ] && [ "$status" -ne 0 ]; then
    fail "round $round (kill after ${delay_ms} ms): exit $status"
  elif cmp -s "$work/previous.atp" "$work/out/model.atp"; then
    before_commit=$((before_commit + 1))
  else
    expect 0 "valid" -- "$atp" verify "$work/out/model.atp"
    cp "$work/previous.atp" "$work/out/model.atp"
  fi
  [ -z "$(ls -A "$work/scratch")" ] || fail "scratch files left after a kill: $(ls -A "$work/scratch")"
  [ "$(ls -A "$work/out")" = "model.atp" ] || fail "left behind: $(ls -A "$work/out" | tr '\n' ' ')"
done
echo "SIGKILL: $before_commit of 8 builds killed before their model was complete (a build takes ${build_ms} ms)"
[ "$before_commit" -gt 0 ] || fail "no build was killed before completing: the test proved nothing"

# --- Unreadable input.
expect 1 "no-such.ply: cannot open: No such file or directory" -- \
  "$atp" build "$work/no-such.ply" -o "$work/out/model.atp" --quiet
mkdir "$work/directory.ply"
expect 1 "directory.ply: not a regular file" -- "$atp" build "$work/directory.ply" -o "$work/out/model.atp" --quiet
cp "$input" "$work/locked.ply"
chmod 000 "$work/locked.ply"
if [ "$(id -u)" -eq 0 ]; then
  # Root reads anything: the build runs as nobody, who may write the output directory.
  chmod 777 "$work/out"
  as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
else
  as_user=()
fi
expect 1 "locked.ply: cannot open: Permission denied" -- \
  "${as_user[@]}" "$atp" build "$work/locked.ply" -o "$work/out/model.atp" --quiet
only_previous "$work/out"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
