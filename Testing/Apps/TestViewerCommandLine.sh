#!/usr/bin/env bash
# atp-view scripted from the command line (needs a display: xvfb-run -a ctest): `atp view`
# runs it, a screenshot of the converged view, a camera path recorded and played back, and one
# clear line plus a non-zero exit code for a model it cannot open or a display it cannot reach.
#   TestViewerCommandLine.sh ATP_BINARY DATA_DIR
set -u
atp=$1
data=$2
source "$(dirname "$0")/expect.sh"

# is_png FILE: a PNG image (its signature) of some size.
is_png() {
  if [ "$(head -c 8 "$1" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] &&
    [ "$(stat -c %s "$1")" -gt 1000 ]; then
    passed=$((passed + 1))
  else
    fail "$1 is not a PNG screenshot"
  fi
}

expect 0 "usage: atp view \[MODEL\]" -- "$atp" view --help
expect 2 "unknown option --bogus" -- "$atp" view --bogus
expect 2 "expected from 0 to 1 argument" -- "$atp" view a.atp b.atp
# Mistakes in the command line are reported before Qt starts: no display needed.
expect 2 "a volume needs --iso VALUE" -- env -u DISPLAY "$atp" view brain.nii.gz
expect 2 "screenshot needs a MODEL" -- env -u DISPLAY "$atp" view --screenshot x.png
expect 2 "tolerance must be a number" -- env -u DISPLAY "$atp" view a.atp --tolerance fine

"$atp" build "$data/bumpy-torus.ply" -o "$work/torus.atp" --quiet >/dev/null || fail "atp build"
# What a session writes is checked before it starts: a screenshot or a recording never replaces
# the model or the path played, and names say what the files hold.
cp "$work/torus.atp" "$work/kept.atp"
expect 2 "screenshot .*kept.atp: a name ending in .png" -- env -u DISPLAY "$atp" view "$work/kept.atp" --screenshot "$work/kept.atp"
expect 2 "record .*kept.atp: a name ending in .camera" -- env -u DISPLAY "$atp" view "$work/kept.atp" --record "$work/kept.atp"
expect 2 "output .*bumpy.ply: a name ending in .atp" -- env -u DISPLAY "$atp" view "$data/bumpy-torus.ply" -o "$work/bumpy.ply"
printf '0 0 0 5 0 0 0 0 0 1 30\n' > "$work/path.camera"
expect 2 "record .*path.camera: is the input .*path.camera: refusing to replace it" -- \
  env -u DISPLAY "$atp" view "$work/kept.atp" --play "$work/path.camera" --record "$work/path.camera"
expect 2 "record .*nowhere/r.camera: No such file or directory" -- \
  env -u DISPLAY "$atp" view "$work/kept.atp" --record "$work/nowhere/r.camera" --screenshot "$work/early.png"
[ ! -e "$work/early.png" ] || fail "a screenshot was written before a bad recording path was refused"
cmp -s "$work/torus.atp" "$work/kept.atp" || fail "a session replaced its model"
expect 0 "" -- "$atp" view "$work/torus.atp" --size 320x240 --tolerance 4 --record "$work/still.camera" \
  --screenshot "$work/still.png"
is_png "$work/still.png"

# A corrupt patch fails a scripted session: its picture would miss what was asked for.
cp "$work/torus.atp" "$work/corrupt.atp"
patches=$(od -An -t u8 -j 56 -N 8 "$work/corrupt.atp" | tr -d ' ')
size=$(stat -c %s "$work/corrupt.atp")
for ((offset = patches + 100; offset < size; offset += 997)); do
  printf '\xa5' | dd of="$work/corrupt.atp" bs=1 seek="$offset" conv=notrunc status=none
done
expect 1 "^atp view: error: .*corrupt.atp: node [0-9]+: patch checksum mismatch: the patch is corrupt" -- \
  "$atp" view "$work/corrupt.atp" --size 320x240 --tolerance 4 --screenshot "$work/corrupt.png"
[ ! -e "$work/corrupt.png" ] || fail "a screenshot of a model with corrupt patches was saved"
grep -qE '^0 ' "$work/still.camera" && passed=$((passed + 1)) || fail "no keyframe recorded at time 0"

# Half a turn around the torus's axis (z), played back, then the screenshot.
cat >"$work/turn.camera" <<'PATH'
# time  position  focal point  view up  view angle
0    0 0 8   0 0 0   0 1 0   30
0.3  0 -8 0.1  0 0 0   0 0 1   30
PATH
expect 0 "" -- "$atp" view "$work/torus.atp" --size 320x240 --tolerance 4 --play "$work/turn.camera" \
  --screenshot "$work/turn.png"
is_png "$work/turn.png"
cmp -s "$work/still.png" "$work/turn.png" && fail "the played path did not move the camera" || passed=$((passed + 1))

# A mesh is built first (here into --output), then shown.
expect 0 "" -- "$atp" view "$data/bumpy-torus.ply" -o "$work/built.atp" --size 320x240 --tolerance 4 \
  --screenshot "$work/built.png"
is_png "$work/built.png"
[ -s "$work/built.atp" ] && passed=$((passed + 1)) || fail "no model built from the mesh"
# A mesh that builds with a warning: told on stderr, and the session goes on to its screenshot.
torus_obj 1 160 80 > "$work/turned.obj"
expect 0 "^atp view: warning: the input's triangles are wound either way at random" -- \
  "$atp" view "$work/turned.obj" -o "$work/turned.atp" --size 320x240 --screenshot "$work/turned.png"
is_png "$work/turned.png"

# Mistakes a user can make: one line naming the file, exit code 1, no screenshot.
head -c 3000 "$work/torus.atp" >"$work/truncated.atp"
expect 1 "error: .*truncated.atp" -- "$atp" view "$work/truncated.atp" --screenshot "$work/bad.png"
echo "1 2 3" >"$work/bad.camera"
expect 1 "error: .*bad.camera:1:" -- "$atp" view "$work/torus.atp" --play "$work/bad.camera" --screenshot "$work/bad.png"
# No display to open a window on: the same, where Qt would abort.
expect 1 "^atp view: error: no display to open a window on" -- \
  env -u DISPLAY -u WAYLAND_DISPLAY -u QT_QPA_PLATFORM "$atp" view "$work/torus.atp" --screenshot "$work/bad.png"
expect 1 "atp view: error: cannot open a window" -- \
  env -u WAYLAND_DISPLAY -u QT_QPA_PLATFORM DISPLAY=:9876 "$atp" view "$work/torus.atp" --screenshot "$work/bad.png"
[ ! -e "$work/bad.png" ] && passed=$((passed + 1)) || fail "a failed session wrote a screenshot"
echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
