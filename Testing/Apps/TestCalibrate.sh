#!/usr/bin/env bash
# atp calibrate on the sample mesh: it finds a scale, stores it (and only it), the stored scale
# passes its own check, and a tiny scale fails it: the picture comparison can fail.
#   TestCalibrate.sh ATP_BINARY DATA_DIR
set -u
# Offscreen pictures here go through X, and once through EGL without a display (below).
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null; then
  exec xvfb-run -a bash "$0" "$@"
fi
atp=$1
data=$2
source "$(dirname "$0")/expect.sh"

small=(--views 3 --size 160x120)
expect 0 "--threshold T" -- "$atp" calibrate --help
expect 2 "size must be" -- "$atp" calibrate "$data/bumpy-torus.ply" --size 100
expect 1 "not an ATP model" -- "$atp" calibrate "$data/bumpy-torus.ply" "${small[@]}"
expect 0 "done:" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --quiet
cp "$work/x.atp" "$work/original.atp"

expect 0 "dry run: .* left unchanged" -- "$atp" calibrate "$work/x.atp" "${small[@]}" --dry-run
cmp -s "$work/x.atp" "$work/original.atp" || { echo "FAIL: --dry-run changed the model"; failures=$((failures + 1)); }

# A model the scale cannot be stored in is said before the search, not after it: a file not
# ours to write, or for root (who writes any file) one on a read-only mount.
cp "$work/original.atp" "$work/readonly.atp"
chmod 444 "$work/readonly.atp"
readonly_calibrate=("$atp" calibrate "$work/readonly.atp" "${small[@]}")
if [ "$(id -u)" -eq 0 ]; then
  if unshare -m true 2>/dev/null; then
    readonly_calibrate=(unshare -m bash -c 'f=$1; shift; mount --bind "$f" "$f" && mount -o remount,ro,bind "$f" && exec "$@"' \
      -- "$work/readonly.atp" "${readonly_calibrate[@]}")
  else
    readonly_calibrate=()
    echo "root without mount namespaces: no read-only model to calibrate"
  fi
fi
if [ ${#readonly_calibrate[@]} -gt 0 ]; then
  expect 1 "^atp calibrate: error: .*readonly.atp: cannot store the scale in it: (Read-only file system|Permission denied)" -- \
    "${readonly_calibrate[@]}"
  [ "$(wc -l <<<"$out")" -eq 1 ] || fail "calibrate searched before saying the model cannot be written"
fi

expect 0 "stored error scale [0-9.e+-]+ in" -- "$atp" calibrate "$work/x.atp" "${small[@]}"
echo "$out"
scale=$(sed -nE 's/^stored error scale ([0-9.e+-]+) in .*/\1/p' <<<"$out")
expect 0 "error scale $scale," -- "$atp" info "$work/x.atp"
expect 0 "x.atp: valid" -- "$atp" verify "$work/x.atp"
# Only the header changed.
cmp -s <(tail -c +417 "$work/x.atp") <(tail -c +417 "$work/original.atp") || { echo "FAIL: calibrate changed more than the header"; failures=$((failures + 1)); }

# The scale found shows no difference; one far below it does, in at least one view.
expect 0 "scale $scale: no visible difference in 3 views" -- "$atp" calibrate "$work/x.atp" "${small[@]}" --check "$scale"
expect 1 "scale 0.001: visible differences in [1-3] of 3 views" -- "$atp" calibrate "$work/x.atp" "${small[@]}" --check 0.001
echo "$out"

# Without a display the pictures come from an EGL device: the same verdicts.
expect 0 "scale $scale: no visible difference in 3 views" -- env -u DISPLAY "$atp" calibrate "$work/x.atp" "${small[@]}" --check "$scale"
expect 1 "scale 0.001: visible differences in [1-3] of 3 views" -- env -u DISPLAY "$atp" calibrate "$work/x.atp" "${small[@]}" --check 0.001

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
