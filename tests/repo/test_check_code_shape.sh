#!/usr/bin/env bash
# Tests of scripts/check_code_shape.sh: the repository holds its shape, and a
# made-up tree with one function of 81 lines, one header with 41 comment lines
# first and a README of 201 lines gives exactly those three violations.
set -euo pipefail
src=$1
script=$src/scripts/check_code_shape.sh
fail() { echo "FAIL $*"; exit 1; }

out=$(bash "$script" "$src") || fail "the repository: $out"
echo "$out"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/calib" "$tmp/run"
{ echo "int long_one() {"; for i in $(seq 79); do echo "  int a$i = $i;"; done; echo "}"; } > "$tmp/calib/long.cpp"   # 81 lines
{ echo "int short_one() {"; for i in $(seq 78); do echo "  int a$i = $i;"; done; echo "}"; } > "$tmp/run/short.cpp"  # 80 lines
{ for i in $(seq 41); do echo "// note $i"; done; echo "#pragma once"; echo "int f();"; } > "$tmp/calib/noted.hpp"
{ for i in $(seq 40); do echo "// note $i"; done; echo "#pragma once"; echo "int g();"; } > "$tmp/run/fine.hpp"
seq 201 > "$tmp/README.md"
rc=0; out=$(bash "$script" "$tmp") || rc=$?
echo "$out"
[[ $rc == 1 ]] || fail "exit $rc on a tree with violations (expected 1)"
[[ $(grep -c . <<< "$out") == 3 ]] || fail "expected 3 violations"
grep -q "calib/long.cpp: function long_one is 81 lines" <<< "$out" || fail "the long function"
grep -q "calib/noted.hpp: 41 comment lines" <<< "$out" || fail "the header"
grep -q "README.md: 201 lines" <<< "$out" || fail "the README"
if grep -q "short_one\|fine.hpp" <<< "$out"; then fail "a function or header at the limit reported"; fi
echo "PASS"
