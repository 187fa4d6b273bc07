#!/usr/bin/env bash
# atp bench on the sample mesh: a few frames of the flythrough in a small window, the CSV's
# rows and columns, the summary, the plot and final frame as PNGs of the asked size that are not
# blank, the speed-up line with --compare-full, and one line plus a non-zero exit code (and no
# file left behind) for each mistake a user can make.
#   TestBench.sh ATP_BINARY DATA_DIR CHECKPNG_BINARY
set -u
# The bench draws through X here, on Xvfb when there is no display (EGL is tested below).
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run > /dev/null; then
  exec xvfb-run -a bash "$0" "$@"
fi
atp=$1
data=$2
checkpng=$3
source "$(dirname "$0")/expect.sh"

columns=frame,seconds,patches,triangles,cache_hits,cache_misses,uploads,upload_bytes,cache_bytes,cut_seconds,upload_seconds,draw_seconds,converged
# check_csv FILE FRAMES: the header, then one row per frame numbered from 0, 13 numbers each,
# every frame drawing triangles.
check_csv() {
  local file=$1 frames=$2
  [ "$(head -1 "$file")" = "$columns" ] || fail "$file: header is '$(head -1 "$file")'"
  [ "$(wc -l < "$file")" -eq $((frames + 1)) ] || fail "$file: $(wc -l < "$file") lines, want $((frames + 1))"
  awk -F, -v frames="$frames" 'NR > 1 {
      if (NF != 13 || $1 != NR - 2 || $2 <= 0 || $4 <= 0) bad = 1
      for (i = 1; i <= NF; ++i) if ($i !~ /^[0-9.e+-]+$/) bad = 1
    } END { exit bad || NR != frames + 1 }' "$file" || fail "$file: bad rows: $(cat "$file")"
}

expect 0 "done:" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/t.atp" --quiet
small=(--frames 4 --size 96x64 --quiet)
expect 0 "--compare-full INPUT" -- "$atp" bench --help

# Files: CSV, plot, final frame, and the comparison ending the summary.
expect 0 "speedup=[0-9.]+ image_difference=[0-9.]+" -- "$atp" bench "$work/t.atp" "${small[@]}" \
  --csv "$work/f.csv" --plot "$work/p.png" --plot-size 320x400 --image "$work/i.png" \
  --compare-full "$data/bumpy-torus.ply"
tail -1 <<<"$out" | grep -qE "^speedup=[0-9.]+ image_difference=[0-9.]+ " || fail "the summary does not end with the speedup line: $out"
grep -qE "^atp: frame time median [0-9.]+ ms" <<<"$out" || fail "no frame time in the summary: $out"
grep -qE "^full: .*bumpy-torus.ply, 186920 triangles" <<<"$out" || fail "no full-resolution line: $out"
check_csv "$work/f.csv" 4
"$checkpng" "$work/i.png" 96 64 || fail "the final frame"
"$checkpng" "$work/p.png" 320 400 || fail "the plot"
# The full mesh in another format, read by VTK's reader for it.
expect 0 "wrote .*full.vtp: 186920 triangles" -- "$atp" extract "$work/t.atp" --level 60 -o "$work/full.vtp"
expect 0 "^speedup=[0-9.]+ image_difference=[0-9.]+ " -- "$atp" bench "$work/t.atp" --frames 2 --size 64x48 --quiet --compare-full "$work/full.vtp"
rm "$work/full.vtp"
# The check can fail: a black 96x64 PNG is blank, and of another size than asked.
base64 -d > "$work/blank.png" <<<"iVBORw0KGgoAAAANSUhEUgAAAGAAAABACAIAAABqVuVZAAAAKUlEQVR42u3BAQ0AAADCoPdPbQ43oAAAAAAAAAAAAAAAAAAAAAAAgDcDSEAAARhzOZwAAAAASUVORK5CYII="
expect 1 "blank.png: 96x64, 0.0% of the pixels differ" -- "$checkpng" "$work/blank.png" 96 64
expect 1 "blank.png: 96x64 .*expected 97x64" -- "$checkpng" "$work/blank.png" 97 64
expect 1 "f.csv: not a PNG" -- "$checkpng" "$work/f.csv" 96 64
rm "$work/blank.png"

# CSV on standard output, the summary on standard error.
stdout=$("$atp" bench "$work/t.atp" --frames 3 --size 64x48 --quiet --no-prefetch --cache 16 2> "$work/summary")
[ $? -eq 0 ] || fail "bench with the CSV on standard output failed: $(cat "$work/summary")"
printf '%s\n' "$stdout" > "$work/stdout.csv"
check_csv "$work/stdout.csv" 3
grep -qE "^model: .*3 frames at 64x48, tolerance 1 px, cache 16 MiB, prefetch off" "$work/summary" || fail "summary: $(cat "$work/summary")"
grep -q "speedup=" "$work/summary" && fail "a speedup line without --compare-full"

# Mistakes: one line, a non-zero exit code, and no file.
expect 1 "missing.atp: cannot open" -- "$atp" bench "$work/missing.atp"
expect 1 "bumpy-torus.ply: not an ATP model" -- "$atp" bench "$data/bumpy-torus.ply"
expect 2 "--frames must be a whole number" -- "$atp" bench "$work/t.atp" --frames 1
expect 2 "--size must be WIDTHxHEIGHT" -- "$atp" bench "$work/t.atp" --size 96
expect 2 "--tolerance must be a number" -- "$atp" bench "$work/t.atp" --tolerance 0
expect 2 "--cache must be a whole number" -- "$atp" bench "$work/t.atp" --cache -3
expect 2 "unknown option --bogus" -- "$atp" bench "$work/t.atp" --bogus
expect 2 "option --plot needs a value" -- "$atp" bench "$work/t.atp" --plot
expect 2 "--plot must name a .png file" -- "$atp" bench "$work/t.atp" --plot "$work/p.jpg"
expect 2 "--image must name a .png file" -- "$atp" bench "$work/t.atp" --image "$work/i"
expect 2 "--image .*same.png: another output is written there too" -- "$atp" bench "$work/t.atp" --plot "$work/same.png" --image "$work/./same.png"
[ ! -e "$work/same.png" ] || fail "bench wrote an output before refusing two under one name"
expect 2 "--compare-full must name a .ply, .obj, .stl or .vtp" -- "$atp" bench "$work/t.atp" --compare-full "$work/m.dae"
mkdir "$work/no"
expect 1 "p.png: cannot write the plot: No such file" -- "$atp" bench "$work/t.atp" "${small[@]}" --plot "$work/no/dir/p.png"
expect 1 "f.csv: cannot write the CSV: No such file" -- "$atp" bench "$work/t.atp" "${small[@]}" --csv "$work/no/dir/f.csv"
expect 1 "no: cannot write the CSV: is a directory" -- "$atp" bench "$work/t.atp" "${small[@]}" --csv "$work/no"
expect 1 "missing.ply: cannot open" -- "$atp" bench "$work/t.atp" "${small[@]}" --compare-full "$work/missing.ply" --csv "$work/x.csv"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n' > "$work/truncated.ply"
expect 1 "truncated.ply: truncated" -- "$atp" bench "$work/t.atp" "${small[@]}" --compare-full "$work/truncated.ply" --csv "$work/x.csv"
# No X server: the bench draws on an EGL device instead (Mesa's software device here, a GPU
# on a headless GPU machine), the same picture as through X.
expect 0 "^renderer: " -- env -u DISPLAY "$atp" bench "$work/t.atp" "${small[@]}" --csv "$work/x.csv" --image "$work/egl.png"
"$atp" bench "$work/t.atp" "${small[@]}" --quiet --csv "$work/x.csv" --image "$work/x11.png" > /dev/null ||
  fail "the same bench through X failed"
cmp -s "$work/egl.png" "$work/x11.png" || fail "the EGL and X pictures differ"
rm -f "$work/egl.png" "$work/x11.png" "$work/x.csv"
# Neither an X server nor an EGL device (VTK's X11 window would abort the process).
expect 1 "needs an X display or an EGL device here \(EGL finds no device\); without either, run under xvfb-run -a" -- env -u DISPLAY __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$atp" bench "$work/t.atp" "${small[@]}" --csv "$work/x.csv"
expect 1 "cannot open the X display ':4321'" -- env DISPLAY=:4321 "$atp" bench "$work/t.atp" "${small[@]}" --csv "$work/x.csv"
# A model with corrupt coarse patches: the renderer's error, once, as the command's. The zeros
# start past the node section (29 KiB of this 1.8 MiB model) and cover levels 0 to 2, which
# every frame of the small window draws: the roots are decoded before the first frame.
size=$(stat -c %s "$work/t.atp")
cp "$work/t.atp" "$work/bad.atp"
dd if=/dev/zero of="$work/bad.atp" bs=1 seek=$((size / 50)) count=$((size / 10)) conv=notrunc status=none
expect 1 "^atp bench: error: .*bad.atp: node [0-9]+: patch checksum mismatch" -- "$atp" bench "$work/bad.atp" "${small[@]}" --csv "$work/x.csv" --image "$work/x.png"
[ "$(grep -c . <<<"$out")" -eq 1 ] || fail "more than one line for a corrupt model: $out"
# A full disk (a file size limit stands in for it) while writing the plot.
expect 1 "full.png: cannot write the plot" -- bash -c "ulimit -f 8; exec '$atp' bench '$work/t.atp' ${small[*]} --csv '$work/x.csv' --plot '$work/full.png'"
rmdir "$work/no"
leftovers=$(ls "$work" | grep -E 'partial|^x\.|full|no')
[ -z "$leftovers" ] || fail "files left behind: $leftovers"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
