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
