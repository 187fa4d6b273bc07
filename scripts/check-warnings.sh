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

# First, that the compiler still rejects a violation with these flags: one struct of two
# layouts in two files.
canary=$(mktemp -d)
trap 'rm -rf "$canary"' EXIT
printf 'struct Cone { float Axis[3]; };\nfloat First(const Cone& c) { return c.Axis[0]; }\n' \
  > "$canary/a.cxx"
printf 'struct Cone { double Axis[3]; };\nfloat First(const Cone& c);\nint main() { return int(First(Cone{})); }\n' \
  > "$canary/b.cxx"
if c++ -O2 -flto=auto -Werror=odr "$canary/a.cxx" "$canary/b.cxx" -o "$canary/odr" 2> "$canary/log" ||
  ! grep -q "One Definition Rule" "$canary/log"; then
  echo "check-warnings: the compiler no longer reports a one-definition-rule violation:" >&2
  cat "$canary/log" >&2
  exit 1
fi

cmake -S . -B build-warnings -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-Werror"
cmake --build build-warnings
cmake -S . -B build-odr -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=ON \
  -DCMAKE_CXX_FLAGS="-Werror=odr -Werror=lto-type-mismatch"
cmake --build build-odr --target atp atp-view
echo "no warnings, no one-definition-rule violation"
