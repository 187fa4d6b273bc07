#!/usr/bin/env bash
# The newcomer's one command: installs the Debian packages, builds everything, and runs the
# main job on the bundled sample mesh (Data/bumpy-torus.ply).
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
