#!/usr/bin/env bash
# Builds the command-line tool and the viewer with link-time optimization, the only build in
# which GCC checks the one-definition rule across translation units (-Wodr): two different types
# of one name in one program, which corrupts memory once the linker keeps one of their template
# instantiations, fail the build. A build of its own because LTO links are slow and every test
# executable would pay for them.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${ATP_ODR_BUILD_DIR:-build-odr}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=ON \
  -DCMAKE_CXX_FLAGS="-Werror=odr -Werror=lto-type-mismatch"
cmake --build "$build_dir" --target atp atp-view
echo "one-definition rule: no violation across atp and atp-view"
