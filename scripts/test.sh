#!/usr/bin/env bash
# Builds if needed and runs the whole test suite with CTest, under a virtual X display so
# rendering tests work headless.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build_dir=${ATP_BUILD_DIR:-build}
# --no-tests=error: a configuration that lost its tests must fail, not pass empty.
bash scripts/headless.sh ctest --test-dir "$build_dir" --output-on-failure --no-tests=error -j "$(nproc)"
