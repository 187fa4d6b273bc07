#!/usr/bin/env bash
# The atp command line as a user meets it: help texts, a build on the sample mesh, and one
# clear line plus a non-zero exit code for each mistake a user can make.
#   TestCommandLine.sh ATP_BINARY DATA_DIR
set -u
atp=$1
data=$2
source "$(dirname "$0")/expect.sh"

expect 0 "commands:" -- "$atp" --help
expect 2 "usage: atp" -- "$atp"
expect 0 "--leaf-capacity N" -- "$atp" build --help
expect 0 "--triangles N" -- "$atp" generate --help
expect 2 "unknown command 'frobnicate'" -- "$atp" frobnicate
expect 2 "unknown option --bogus" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --bogus
expect 2 "missing -o" -- "$atp" build "$data/bumpy-torus.ply"
expect 2 "leaf-capacity must be a whole number" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --leaf-capacity lots
expect 2 "expected 1 argument" -- "$atp" build -o "$work/x.atp"

# The main job on the bundled sample.
expect 0 "done: .* triangles/s, peak memory" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --quiet
expect 0 "partition: [0-9]+ leaves" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --leaf-capacity 500 --bucket-memory 1
[ -s "$work/x.atp" ] || { echo "FAIL: atp build wrote no model"; failures=$((failures + 1)); }
expect 0 "cpu: partition [0-9.]+s, construction [0-9.]+s in this process; jobs: leaves [0-9.]+s" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --quiet
# On a terminal (script gives the build one) a progress bar with rate and ETA; off one, a line
# per tenth with the time elapsed.
expect 0 "simplifying \[#+ *\] +[0-9.]+%  [0-9.]+k? triangles/s  ETA [0-9]+:[0-9][0-9]" -- \
  script -qec "$(printf '%q ' "$atp" build "$data/bumpy-torus.ply" -o "$work/eta.atp")" /dev/null
expect 0 "simplifying: +100%  .*elapsed [0-9]+:[0-9][0-9]" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/eta.atp"
grep -q "ETA" <<<"$out" && fail "ETA off a terminal"
expect 0 "simplify: [0-9]+ diamonds" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/y.atp" --threads 1 --patch-budget 1000
expect 0 "model: [0-9]+ nodes, [0-9]+ levels" -- "$atp" info "$work/x.atp"
expect 0 '"bytes_per_input_triangle"' -- "$atp" info --json "$work/x.atp"
expect 0 '"cache_order": "best"' -- "$atp" info --json "$work/x.atp"
# A file name is bytes: quotes, backslashes, control characters and what is not UTF-8 are escaped.
odd="$work/$(printf 'q"b\\c\001\377.atp')"
cp "$work/x.atp" "$odd"
expect 0 '^\{"file": ".*/q\\"b\\\\c\\u0001\\ufffd\.atp", "version"' -- "$atp" info --json "$odd"
rm -f "$odd"
expect 0 "done: " -- "$atp" build "$data/bumpy-torus.ply" -o "$work/fast.atp" --quiet --fast-cache-order

# Triangles wound at random build, with a warning after the figures; wound one way, none.
torus_obj 1 80 40 > "$work/turned.obj"
expect 0 "atp build: warning: the input's triangles are wound either way at random \(in [0-9]+ of [0-9]+ diamonds\)" -- "$atp" build "$work/turned.obj" -o "$work/turned.atp" --quiet --leaf-capacity 500
[[ "$(tail -n 1 <<<"$out")" == "atp build: warning: "* ]] || fail "the warning should follow the figures: $out"
torus_obj 0 80 40 > "$work/facing-out.obj"
expect 0 "done: " -- "$atp" build "$work/facing-out.obj" -o "$work/facing-out.atp" --quiet --leaf-capacity 500
grep -q "warning" <<<"$out" && fail "a torus wound one way was warned about: $out"
rm -f "$work/turned.obj" "$work/turned.atp" "$work/facing-out.obj" "$work/facing-out.atp"
expect 0 "patch budget 2000, fast cache order," -- "$atp" info "$work/fast.atp"
expect 0 "fast.atp: valid" -- "$atp" verify "$work/fast.atp"
expect 0 "x.atp: valid" -- "$atp" verify "$work/x.atp"
# Corruption anywhere and truncation: verify says so with exit code 1.
cp "$work/x.atp" "$work/bad.atp"
size=$(stat -c %s "$work/bad.atp")
offset=$((size * 2 / 3))
byte=$(od -An -tu1 -j "$offset" -N1 "$work/bad.atp" | tr -d ' ')
printf "\\x$(printf %02x $(((byte + 1) % 256)))" | dd of="$work/bad.atp" bs=1 seek="$offset" conv=notrunc status=none
expect 1 "INVALID" -- "$atp" verify "$work/bad.atp"
head -c $((size / 2)) "$work/x.atp" > "$work/bad.atp"
expect 1 "truncated" -- "$atp" verify "$work/bad.atp"
expect 1 "not an ATP model" -- "$atp" info "$data/bumpy-torus.ply"
rm -f "$work/bad.atp"
expect 2 "patch-budget must be" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --patch-budget 3

# Bad input: one line naming the file and the problem.
expect 1 "missing.ply" -- "$atp" build "$work/missing.ply" -o "$work/x.atp"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n' > "$work/truncated.ply"
expect 1 "truncated.ply" -- "$atp" build "$work/truncated.ply" -o "$work/x.atp"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n' > "$work/nan.ply"
expect 1 "nan.ply.*(non-finite|nan)" -- "$atp" build "$work/nan.ply" -o "$work/x.atp"
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n' > "$work/empty.ply"
expect 1 "empty.ply.*empty" -- "$atp" build "$work/empty.ply" -o "$work/x.atp"
# Coordinates near FLT_MAX would give a model of infinite bounds: refused; large ones build.
printf 'v -3e38 -3e38 -3e38\nv 3e38 -3e38 -3e38\nv 0 3e38 -3e38\nv 0 0 3e38\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 1 3 4\n' > "$work/huge.obj"
expect 1 "huge.obj: a coordinate of magnitude 3e\+38; .* within \+-1e\+36" -- "$atp" build "$work/huge.obj" -o "$work/huge.atp"
sed 's/3e38/1e35/g' "$work/huge.obj" > "$work/large.obj"
expect 0 "done: " -- "$atp" build "$work/large.obj" -o "$work/large.atp" --quiet
expect 0 "large.atp: valid" -- "$atp" verify "$work/large.atp"
rm -f "$work/huge.obj" "$work/large.obj" "$work/large.atp"
# A FIFO is no input file (opening it would wait for a writer), nor an output to replace.
mkfifo "$work/fifo.ply" "$work/fifo.atp"
expect 1 "fifo.ply: not a regular file" -- timeout 60 "$atp" build "$work/fifo.ply" -o "$work/x.atp"
expect 1 "fifo.atp: not a regular file" -- timeout 60 "$atp" info "$work/fifo.atp"
expect 1 "fifo.atp: exists and is not a regular file: refusing to replace it" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/fifo.atp"
[ -p "$work/fifo.atp" ] || fail "the FIFO given as output was replaced"
rm -f "$work/fifo.ply" "$work/fifo.atp"
# Nor may a build replace its own input, or start with a name its side file cannot extend.
cp "$data/bumpy-torus.ply" "$work/self.ply"
expect 2 "-o .*self.ply: a model is written to a name ending in .atp" -- "$atp" build "$work/self.ply" -o "$work/self.ply"
cmp -s "$data/bumpy-torus.ply" "$work/self.ply" || fail "a build replaced its own input"
rm -f "$work/self.ply"
expect 1 "file name too long" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/$(printf 'a%.0s' $(seq 240)).atp"
deep=$work
for i in $(seq 16); do deep=$deep/$(printf 'd%.0s' $(seq 250)); done
mkdir -p "$deep"
expect 1 "path too long" -- "$atp" build "$data/bumpy-torus.ply" -o "$deep/$(printf 'a%.0s' $(seq 50)).atp"
rm -rf "$work/ddd"*
expect 1 "scratch" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --scratch "$work/no/such/dir"
# A failed build leaves an existing model as it was.
cp "$work/x.atp" "$work/keep.atp"
expect 1 "truncated.ply" -- "$atp" build "$work/truncated.ply" -o "$work/keep.atp"
cmp -s "$work/x.atp" "$work/keep.atp" || { echo "FAIL: a failed build changed the existing model"; failures=$((failures + 1)); }

# An input truncated by another program while mapped raises SIGBUS on the next read past its
# new end: a message and exit code 1, no model, however the truncation falls (before the read:
# the reader's own check; during it: the handler). A fast machine may have read the whole input
# before a late truncation: that build must then be whole, holding every input triangle.
"$atp" generate -n 2000000 -o "$work/bus.ply" > /dev/null
refused=0
for delay in 0.05 0.1 0.2 0.3; do
  cp "$work/bus.ply" "$work/cut.ply"
  rm -f "$work/bus.atp"
  "$atp" build "$work/cut.ply" -o "$work/bus.atp" --threads 1 --quiet > "$work/bus.out" 2>&1 &
  pid=$!
  sleep "$delay"
  truncate -s 1000 "$work/cut.ply"
  wait "$pid"
  status=$?
  if [ "$status" -eq 1 ] && grep -qE "a mapped file could not be read|cut.ply: truncated" "$work/bus.out" &&
    [ ! -e "$work/bus.atp" ]; then
    refused=$((refused + 1))
  elif [ "$status" -eq 0 ] && grep -q "done: .*bus.atp: 2.00M triangles" "$work/bus.out" &&
    "$atp" verify "$work/bus.atp" > /dev/null 2>&1; then
    : # read whole before the truncation
  else
    fail "input truncated after ${delay}s: exit $status, $(cat "$work/bus.out")"
  fi
done
[ "$refused" -gt 0 ] || fail "no truncation fell before the input was read: the refusal went untested"
rm -f "$work/bus.atp"
# Any other SIGBUS (here sent, not raised by an access) is a message and exit code 1 too.
"$atp" build "$work/bus.ply" -o "$work/bus.atp" --threads 1 --quiet > "$work/bus.out" 2>&1 &
pid=$!
sleep 0.3
if kill -BUS "$pid" 2> /dev/null; then
  wait "$pid"
  status=$?
  { [ "$status" -eq 1 ] && grep -q "atp: error: bus error" "$work/bus.out" && [ ! -e "$work/bus.atp" ]; } ||
    fail "SIGBUS during a build: exit $status, $(cat "$work/bus.out")"
else
  wait "$pid" # done before the signal: nothing to check
fi
rm -f "$work"/bus.* "$work/cut.ply"
# A full scratch disk (a file size limit stands in for it): an error, not a crash.
expect 1 "cannot write scratch data.*(File too large|No space)" -- bash -c "ulimit -f 2048; exec '$atp' build '$data/bumpy-torus.ply' -o '$work/full.atp' --bucket-memory 1 --scratch '$work' --quiet"
[ -z "$(ls "$work" | grep -v -E '^(x|y|keep|fast|eta)\.atp$|\.ply$')" ] || { echo "FAIL: files left behind: $(ls "$work")"; failures=$((failures + 1)); }

# atp extract: a level or a camera's cut as PLY, VTP or STL, read back by the builder's own
# readers; mistakes and failed writes are one line, a non-zero exit and no file.
expect 0 "--level N" -- "$atp" extract --help
expect 0 "wrote .*l6.ply: 186920 triangles from [0-9]+ patches \(level 60\)" -- "$atp" extract "$work/x.atp" --level 60 -o "$work/l6.ply"
expect 0 "input: .* 186.9k triangles \(0 degenerate dropped, 574 boundary edges\)" -- "$atp" build "$work/l6.ply" -o "$work/l6.atp" --quiet
expect 0 "wrote .*far.vtp: [0-9]+ triangles .*the cut at 1 px" -- "$atp" extract "$work/x.atp" --camera 0,0,80,0,0,0 -o "$work/far.vtp" --patch-ids
expect 0 "wrote .*near.stl: [0-9]+ triangles .*the cut at 0.5 px" -- "$atp" extract "$work/x.atp" --camera 0,0,4,0,0,0 --tolerance 0.5 -o "$work/near.stl" --backface
far=$("$atp" extract "$work/x.atp" --camera 0,0,80,0,0,0 -o "$work/far.ply" | sed -E 's/.*: ([0-9]+) triangles.*/\1/')
near=$("$atp" extract "$work/x.atp" --camera 0,0,6,0,0,0 -o "$work/near.ply" | sed -E 's/.*: ([0-9]+) triangles.*/\1/')
[ "$far" -lt "$near" ] || { echo "FAIL: a far camera's cut ($far) is not coarser than a near one's ($near)"; failures=$((failures + 1)); }
expect 2 "must name a .ply, .vtp or .stl" -- "$atp" extract "$work/x.atp" -o "$work/x.obj"
expect 2 "missing -o" -- "$atp" extract "$work/x.atp"
expect 2 "option -o needs a value \(OUT\)" -- "$atp" extract "$work/x.atp" -o ""
expect 2 "option --output needs a value \(OUT.atp\)" -- "$atp" build "$data/bumpy-torus.ply" --output ""
expect 2 "must name a .ply" -- "$atp" extract "$work/x.atp" -o x
# Looking away from the model: an empty mesh, still a valid file.
expect 0 "wrote .*away.ply: 0 triangles from 0 patches" -- "$atp" extract "$work/x.atp" --camera 0,0,30,0,0,60 -o "$work/away.ply"
expect 2 "camera must be 6 comma-separated numbers" -- "$atp" extract "$work/x.atp" --camera 1,2,nan -o "$work/c.ply"
expect 2 "the eye and the focal point are the same point" -- "$atp" extract "$work/x.atp" --camera 1,2,3,1,2,3 -o "$work/c.ply"
expect 2 "--up must be a direction that is not along the view direction" -- "$atp" extract "$work/x.atp" --up 0,0,0 -o "$work/c.ply"
expect 2 "--up must be a direction that is not along the view direction" -- "$atp" extract "$work/x.atp" --up 0,0,1 -o "$work/c.ply"
expect 2 "--camera: coordinates must lie within [+]-1e30" -- "$atp" extract "$work/x.atp" --camera 1e160,0,0,0,0,0 -o "$work/c.ply"
expect 2 "--up must be a direction that is not along the view direction" -- "$atp" extract "$work/x.atp" --camera 0,0,30,0,0,0 --up 0,0,-2 -o "$work/c.ply"
expect 2 "tolerance must be a number" -- "$atp" extract "$work/x.atp" --tolerance 0 -o "$work/c.ply"
expect 1 "not an ATP model" -- "$atp" extract "$data/bumpy-torus.ply" -o "$work/c.ply"
expect 1 "c.ply: cannot write the mesh" -- "$atp" extract "$work/x.atp" -o "$work/no/such/dir/c.ply"
cp "$work/l6.ply" "$work/keep.ply"
for ext in ply vtp stl; do
  expect 1 "full.$ext: cannot write the mesh" -- bash -c "ulimit -f 200; exec '$atp' extract '$work/x.atp' --level 6 -o '$work/full.$ext'"
  expect 1 "keep.ply: cannot write the mesh" -- bash -c "ulimit -f 200; exec '$atp' extract '$work/x.atp' --level 6 -o '$work/keep.ply'"
done
cmp -s "$work/l6.ply" "$work/keep.ply" || { echo "FAIL: a failed extract changed the existing mesh"; failures=$((failures + 1)); }
[ -z "$(ls "$work" | grep -E 'full|partial')" ] || { echo "FAIL: extract left files behind: $(ls "$work")"; failures=$((failures + 1)); }
rm -f "$work"/*.ply "$work"/*.vtp "$work"/*.stl "$work/l6.atp"

# The generator writes a mesh the builder reads back, and never a partial file.
expect 0 "wrote .*g.ply: [0-9]+ triangles" -- "$atp" generate -n 5000 --holes 2 -o "$work/g.ply"
expect 0 "boundary edges" -- "$atp" build "$work/g.ply" -o "$work/g.atp" --quiet
expect 1 "g.ply: cannot write the mesh: No such file" -- "$atp" generate -n 5000 -o "$work/no/such/dir/g.ply"
# PLY under another name would be read as what the name says.
expect 2 "g.obj: the surface is written as PLY, to a name ending in .ply" -- "$atp" generate -n 5000 -o "$work/g.obj"
[ ! -e "$work/g.obj" ] || fail "generate wrote g.obj"
# Interrupted (SIGTERM, SIGHUP, SIGQUIT, a closed pipe; sent by timeout, since a background job
# of a script ignores SIGINT and SIGQUIT): the partial file goes too.
mkdir "$work/interrupted"
for signal in TERM HUP QUIT PIPE; do
  timeout -s "$signal" 0.3 "$atp" generate -n 20000000 -o "$work/interrupted/g.ply" > /dev/null 2>&1
  [ -z "$(ls "$work/interrupted")" ] || fail "SIG$signal left $(ls "$work/interrupted")"
  rm -f "$work/interrupted"/*
done
rmdir "$work/interrupted"

# Volumes: the isosurface of a raw file (any voxel type and byte order, with spacing and origin)
# or a .vti, contoured in slabs; made here with perl (raw) and as text (an ASCII .vti).
expect 0 "--iso VALUE" -- "$atp" build --help
perl -e 'for $k (0..23) { for $j (0..23) { for $i (0..23) {
  $d = sqrt(($i - 11.5)**2 + ($j - 12.2)**2 + ($k - 11.8)**2); $v = int(250 - 20 * $d);
  print pack("C", $v < 0 ? 0 : $v) } } }' > "$work/sphere.raw"
expect 0 "volume: 24x24x24 voxels, values 0 to 2[0-9]{2}, isosurface at 100 in 6 slabs" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --type uint8 --iso 100 --slab 5 -o "$work/v.atp" --quiet
expect 0 "input: .* triangles \(0 degenerate dropped, 0 boundary edges\)" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --iso 100.5 -o "$work/v.atp" --quiet
expect 0 "v.atp: valid" -- "$atp" verify "$work/v.atp"
perl -e 'for $k (0..19) { for $j (0..20) { for $i (0..21) {
  $d = sqrt(($i - 10.5)**2 + ($j - 10.2)**2 + ($k - 9.8)**2);
  print pack("s>", int(3000 - 500 * $d)) } } }' > "$work/sphere-be.raw"
expect 0 "volume: 22x21x20 voxels, values -[0-9]+ to 2[0-9]{3}, isosurface at -1000" -- "$atp" build "$work/sphere-be.raw" --dims 22,21,20 --type int16 --big-endian --iso -1000 --spacing 2,1,0.5 --origin 100,0,0 --slab 3 -o "$work/w.atp" --quiet
expect 0 "box \(10[0-9]\.[0-9]+ [0-9.]+ [0-9.]+\) - \(1[23][0-9]\.[0-9]+ [0-9.]+ [0-9.]+\)" -- "$atp" info "$work/w.atp"
{
  echo '<?xml version="1.0"?>'
  echo '<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">'
  echo '<ImageData WholeExtent="0 9 0 10 0 11" Origin="0 0 0" Spacing="0.5 0.5 0.5">'
  echo '<Piece Extent="0 9 0 10 0 11"><PointData Scalars="density">'
  echo '<DataArray type="Float32" Name="density" format="ascii">'
  awk 'BEGIN { for (k = 0; k < 12; k++) for (j = 0; j < 11; j++) for (i = 0; i < 10; i++)
    printf "%g\n", sqrt((i - 4.6)^2 + (j - 5.1)^2 + (k - 5.4)^2) }'
  echo '</DataArray></PointData><CellData></CellData></Piece></ImageData></VTKFile>'
} > "$work/ball.vti"
expect 0 "volume: 10x11x12 voxels.* in 3 slabs" -- "$atp" build "$work/ball.vti" --iso 3.5 --slab 5 -o "$work/ball.atp" --quiet
expect 0 "ball.atp: valid" -- "$atp" verify "$work/ball.atp"
# Mistakes: usage errors (exit 2) before anything is read, bad volumes one line (exit 1).
expect 2 "volume needs --iso" -- "$atp" build "$work/ball.vti" -o "$work/vx.atp"
expect 2 "volume needs --iso" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 -o "$work/vx.atp"
expect 2 "--iso is for volumes.*bumpy-torus.ply is none of these, and a raw volume needs --dims X,Y,Z" -- "$atp" build "$data/bumpy-torus.ply" --iso 3 -o "$work/vx.atp"
expect 2 "--slab is for volumes" -- "$atp" build "$data/bumpy-torus.ply" --slab 8 -o "$work/vx.atp"
expect 2 "--spacing is for raw volumes, which need --dims" -- "$atp" build "$work/ball.vti" --iso 3 --spacing 1,1,1 -o "$work/vx.atp"
expect 2 "--type must be uint8, int16, uint16 or float32, got 'int64'" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --type int64 --iso 100 -o "$work/vx.atp"
expect 2 "--dims must be 3 comma-separated numbers" -- "$atp" build "$work/sphere.raw" --dims 24,24 --iso 100 -o "$work/vx.atp"
expect 2 "--dims must be 3 whole numbers" -- "$atp" build "$work/sphere.raw" --dims 24,24,0 --iso 100 -o "$work/vx.atp"
expect 2 "--iso must be a number" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --iso nan -o "$work/vx.atp"
expect 2 "--slab must be a whole number from 2" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --iso 100 --slab 1 -o "$work/vx.atp"
expect 1 "sphere.raw: is 13824 bytes, but 24x24x24 uint16 voxels are 27648 bytes" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --type uint16 --iso 100 -o "$work/vx.atp"
expect 1 "sphere.raw: no surface at iso value 900 \(the voxel values range from 0 to 2[0-9]{2}\)" -- "$atp" build "$work/sphere.raw" --dims 24,24,24 --iso 900 -o "$work/vx.atp"
perl -e 'for $n (0..63) { print pack("f<", $n == 37 ? 9**9**9 / 9**9**9 : $n) }' > "$work/nan.raw"
expect 1 "nan.raw: voxel \(1, 1, 2\) is NaN" -- "$atp" build "$work/nan.raw" --dims 4,4,4 --type float32 --iso 10 -o "$work/vx.atp"
expect 1 "missing.nii.gz: cannot open" -- "$atp" build "$work/missing.nii.gz" --iso 10 -o "$work/vx.atp"
printf 'not a volume' > "$work/bad.vti"
expect 1 "bad.vti: not a readable volume" -- "$atp" build "$work/bad.vti" --iso 10 -o "$work/vx.atp"
lines=$("$atp" build "$work/bad.vti" --iso 10 -o "$work/vx.atp" --quiet 2>&1 | wc -l)
[ "$lines" -eq 1 ] || { echo "FAIL: a bad volume gave $lines lines, not one"; failures=$((failures + 1)); }
[ ! -e "$work/vx.atp" ] || { echo "FAIL: a failed volume build left a model"; failures=$((failures + 1)); }

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
