# Shared by the command-line tests: sourced, never run. Counts checks into $passed and $failures;
# `finish` prints the tally and returns non-zero on any failure.
failures=0
passed=0

# fail MESSAGE: one failed check.
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect CODE PATTERN -- command...: exit code CODE and output (stdout+stderr) matching PATTERN.
expect() {
  local code=$1 pattern=$2
  shift 3
  local out status
  out=$("$@" 2>&1)
  status=$?
  if [ "$status" -ne "$code" ] || ! grep -qE -- "$pattern" <<<"$out"; then
    fail "$* -> exit $status (want $code), output:"
    sed 's/^/    /' <<<"$out" | head -20
    echo "    (wanted /$pattern/)"
  else
    passed=$((passed + 1))
  fi
}

finish() {
  echo "$passed passed, $failures failed"
  [ "$failures" -eq 0 ]
}
