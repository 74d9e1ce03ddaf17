# Shared helpers of the command-line contract tests (sourced, not run).
# Sets $tmp (removed on exit), counts passed/failed checks.
#   check NAME EXIT CMD...   runs CMD, stdout -> $tmp/out, stderr -> $tmp/err;
#                            wants exit code EXIT, and for exit 2 exactly one stderr line
#   expect_out NAME REGEX / expect_err NAME REGEX   grep -E in $tmp/out / $tmp/err
#   holds NAME CMD...        CMD succeeds (a test, cmp, grep...)
#   finish                   prints "N passed, M failed" and returns non-zero on failures
fail=0; passed=0
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

check() {
  local name=$1 want=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [[ $got -ne $want ]]; then
    echo "FAIL $name: exit $got, want $want"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  if [[ $want -eq 2 && $(wc -l <"$tmp/err") -ne 1 ]]; then
    echo "FAIL $name: stderr is not one line:"; cat "$tmp/err"; fail=$((fail+1)); return 1
  fi
  passed=$((passed+1))
}
expect_out() {
  if grep -qE -- "$2" "$tmp/out"; then passed=$((passed+1)); else echo "FAIL $1: no '$2' in:"; cat "$tmp/out"; fail=$((fail+1)); fi
}
expect_err() {
  if grep -qE -- "$2" "$tmp/err"; then passed=$((passed+1)); else echo "FAIL $1: no '$2' in:"; cat "$tmp/err"; fail=$((fail+1)); fi
}
holds() {
  local name=$1; shift
  if "$@"; then passed=$((passed+1)); else echo "FAIL $name"; fail=$((fail+1)); fi
}
finish() {
  echo "$passed passed, $fail failed"
  [[ $fail -eq 0 ]]
}
