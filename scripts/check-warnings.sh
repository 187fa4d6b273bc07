#!/usr/bin/env bash
# Two builds of their own that fail on what the everyday build only warns about:
# - build-warnings/: everything (tools, tests, benches) with -Wall -Wextra as errors;
# - build-odr/: atp and atp-view with link-time optimization, the only build in which GCC checks
#   the one-definition rule across source files (-Wodr). Two different types of one name in one
#   program corrupt memory once the linker keeps one of their template instantiations (an LTO
#   build of atp crashed on one). Only that check is an error there: GCC 12 raises false
#   -Wstringop-overflow warnings once LTO inlines across files.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-warnings -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-Werror"
cmake --build build-warnings
cmake -S . -B build-odr -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=ON \
  -DCMAKE_CXX_FLAGS="-Werror=odr -Werror=lto-type-mismatch"
cmake --build build-odr --target atp atp-view
echo "no warnings, no one-definition-rule violation"
