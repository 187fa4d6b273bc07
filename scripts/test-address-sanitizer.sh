#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer, in build-asan/.
# Any report fails its test (-fno-sanitize-recover); leaks are checked except in tests that draw
# (Testing/CMakeLists.txt: llvmpipe leaks from a driver module it has unloaded).
set -euo pipefail
cd "$(dirname "$0")/.."
export ATP_BUILD_DIR=build-asan
if [ ! -f "$ATP_BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$ATP_BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DATP_SANITIZE=address,undefined
fi
export UBSAN_OPTIONS=print_stacktrace=1
bash scripts/test.sh
echo "AddressSanitizer and UndefinedBehaviorSanitizer: no reports"
