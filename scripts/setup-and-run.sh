#!/usr/bin/env bash
# The newcomer's one command: installs the Debian packages, builds everything, and runs the
# main job on the bundled sample mesh (Data/bumpy-torus.ply): a model, a rendered image of it and
# the benchmark plot, written to named files under build/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
bash scripts/build.sh

echo
echo "== atp build Data/bumpy-torus.ply -o build/bumpy-torus.atp"
build/bin/atp build Data/bumpy-torus.ply -o build/bumpy-torus.atp
echo
echo "== atp info build/bumpy-torus.atp"
build/bin/atp info build/bumpy-torus.atp
echo
echo "== atp verify build/bumpy-torus.atp"
build/bin/atp verify build/bumpy-torus.atp
echo
echo "== atp bench build/bumpy-torus.atp: the standard flythrough, offscreen, against the full mesh"
# Offscreen OpenGL still needs an X display: a virtual one when there is none.
display=()
if [ -z "${DISPLAY:-}" ]; then
  display=(bash scripts/headless.sh)
fi
"${display[@]}" build/bin/atp bench build/bumpy-torus.atp --frames 120 \
  --compare-full Data/bumpy-torus.ply --csv build/bumpy-torus-frames.csv \
  --plot build/bumpy-torus-bench.png --image build/bumpy-torus.png
echo
echo "The model:           build/bumpy-torus.atp"
echo "Its last frame:      build/bumpy-torus.png"
echo "The benchmark plot:  build/bumpy-torus-bench.png (frame time, triangles, patches, cache misses)"
echo "Per-frame figures:   build/bumpy-torus-frames.csv"
