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
expect 0 "simplify: [0-9]+ diamonds" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/y.atp" --threads 1 --patch-budget 1000
expect 0 "model: [0-9]+ nodes, [0-9]+ levels" -- "$atp" info "$work/x.atp"
expect 0 '"bytes_per_input_triangle"' -- "$atp" info --json "$work/x.atp"
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
expect 1 "scratch" -- "$atp" build "$data/bumpy-torus.ply" -o "$work/x.atp" --scratch "$work/no/such/dir"
# A failed build leaves an existing model as it was.
cp "$work/x.atp" "$work/keep.atp"
expect 1 "truncated.ply" -- "$atp" build "$work/truncated.ply" -o "$work/keep.atp"
cmp -s "$work/x.atp" "$work/keep.atp" || { echo "FAIL: a failed build changed the existing model"; failures=$((failures + 1)); }

# A full scratch disk (a file size limit stands in for it): an error, not a crash.
expect 1 "cannot write scratch data.*(File too large|No space)" -- bash -c "ulimit -f 2048; exec '$atp' build '$data/bumpy-torus.ply' -o '$work/full.atp' --bucket-memory 1 --scratch '$work' --quiet"
[ -z "$(ls "$work" | grep -v -E '^(x|y|keep)\.atp$|\.ply$')" ] || { echo "FAIL: files left behind: $(ls "$work")"; failures=$((failures + 1)); }

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
expect 2 "must name a .ply" -- "$atp" extract "$work/x.atp" -o x
# Looking away from the model: an empty mesh, still a valid file.
expect 0 "wrote .*away.ply: 0 triangles from 0 patches" -- "$atp" extract "$work/x.atp" --camera 0,0,30,0,0,60 -o "$work/away.ply"
expect 2 "camera must be 6 comma-separated numbers" -- "$atp" extract "$work/x.atp" --camera 1,2,nan -o "$work/c.ply"
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
expect 1 "cannot create" -- "$atp" generate -n 5000 -o "$work/no/such/dir/g.ply"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
