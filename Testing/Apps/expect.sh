# Shared by the command-line tests (sourced): counters, a scratch directory removed on exit,
# and expect.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0
out=""

# expect CODE PATTERN -- command...: exit code CODE and output (stdout+stderr, kept in $out)
# matching PATTERN.
expect() {
  local code=$1 pattern=$2
  shift 3
  local status
  out=$("$@" 2>&1)
  status=$?
  if [ "$status" -ne "$code" ] || ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL: $* -> exit $status (want $code), output:"
    sed 's/^/    /' <<<"$out" | head -30
    echo "    (wanted /$pattern/)"
    failures=$((failures + 1))
  else
    passed=$((passed + 1))
  fi
}

# fail MESSAGE: a failed check that is not a command's exit code and output.
fail() {
  echo "FAIL: $1"
  failures=$((failures + 1))
}

# torus_obj TURN NU NV: a torus of NU x NV quads as OBJ on stdout; with TURN 1, each triangle
# wound either way at random.
torus_obj() {
  awk -v turn="$1" -v nu="$2" -v nv="$3" 'BEGIN {
    srand(7); pi = 3.14159265358979
    for (j = 0; j < nv; ++j) for (i = 0; i < nu; ++i) {
      u = 2 * pi * i / nu; v = 2 * pi * j / nv
      printf "v %.6f %.6f %.6f\n", (1 + 0.4 * cos(v)) * cos(u), (1 + 0.4 * cos(v)) * sin(u), 0.4 * sin(v)
    }
    for (j = 0; j < nv; ++j) for (i = 0; i < nu; ++i) {
      a = j * nu + i + 1; b = j * nu + (i + 1) % nu + 1
      c = ((j + 1) % nv) * nu + (i + 1) % nu + 1; d = ((j + 1) % nv) * nu + i + 1
      if (turn && rand() < 0.5) printf "f %d %d %d\n", a, c, b; else printf "f %d %d %d\n", a, b, c
      if (turn && rand() < 0.5) printf "f %d %d %d\n", a, d, c; else printf "f %d %d %d\n", a, c, d
    }
  }'
}
