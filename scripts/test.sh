#!/usr/bin/env bash
# Builds if needed and runs the whole test suite with CTest, under a virtual X display so
# rendering tests work headless.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build_dir=${ATP_BUILD_DIR:-build}
xvfb-run -a ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
