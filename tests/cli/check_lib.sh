# check_lib.sh - what the shell tests share (source it): pass/fail counters with ok / bad, a
# temporary folder $tmp removed on exit, and check_finish NAME, which prints the counts in the
# line ctest's output shows ("NAME: N passed, M failed") and returns non-zero on a failure.
pass=0
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
check_finish() {
  echo "$1: $pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
