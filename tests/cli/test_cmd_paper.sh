#!/usr/bin/env bash
# Tests of app/cmd_paper.cpp: gpm paper. Default: help, and bad input exits 2
# with one line and creates nothing. With "full" (CTest label long): the
# default run writes paper.md, paper.html, paper.json and the figures, every
# table and figure of the paper is there with both columns, every difference
# has its sentence, and paper.json agrees with paper.md.
set -u
GPM="$1"; MODE="${2:-fast}"
source "$(dirname "$0")/cli_lib.sh"

check help 0 "$GPM" paper --help
expect_out "help names --budget" "--budget"
expect_out "help names the paper's budget" "5e7"

check "budget zero" 2 "$GPM" paper -o "$tmp/zero" --budget 0
expect_err "budget zero message" "--budget: must be a whole number from 1 to 1e10 evaluations, got '0'"
[[ ! -e "$tmp/zero" ]] && passed=$((passed+1)) || { echo "FAIL budget zero left $tmp/zero"; fail=$((fail+1)); }
check "budget fraction" 2 "$GPM" paper -o "$tmp/frac" --budget 1.5
[[ ! -e "$tmp/frac" ]] && passed=$((passed+1)) || { echo "FAIL budget fraction left $tmp/frac"; fail=$((fail+1)); }
check "budget text" 2 "$GPM" paper -o "$tmp/text" --budget lots
check "no output" 2 "$GPM" paper
printf 'not a folder\n' >"$tmp/file"
check "output is a file" 2 "$GPM" paper -o "$tmp/file"
check "negative jobs" 2 "$GPM" paper -o "$tmp/jobs" -j -1

if [[ "$MODE" == full ]]; then
  check "default run" 0 "$GPM" paper -o "$tmp/paper"
  expect_out "summary line" "gpm paper: 11 tables and figures, [0-9]+ rows \([0-9]+ agree, [0-9]+ differ, each explained\)"
  for f in paper.md paper.html paper.json figure3.svg figure4.svg figure5.svg; do
    [[ -s "$tmp/paper/$f" ]] && passed=$((passed+1)) || { echo "FAIL missing $f"; fail=$((fail+1)); }
  done
  if /usr/bin/python3 - "$tmp/paper" <<'PY'
import json, sys
d = sys.argv[1]
j = json.load(open(d + "/paper.json"))
md = open(d + "/paper.md").read()
ids = [t["id"] for t in j["tables"]]
want = ["table1", "table2", "table3", "table4", "table5", "table6", "figure3", "figure4", "figure5", "table7", "table8"]
assert ids == want, ids
for t in j["tables"]:
    assert "## " + t["title"] in md, t["title"]
    assert any(r["paper"] is not None and r["ours"] is not None for r in t["rows"]), t["id"]
    for r in t["rows"]:
        line = "| %s | %s | %s | %s |" % (r["quantity"], r["unit"], r["paper_text"], r["ours_text"])
        assert line in md, line
        if r["reason"] != "agrees":
            assert r["why"].endswith(".") and len(r["why"]) > 20, (t["id"], r["quantity"])
            assert r["why"] in md, r["why"]
        if r["ours"] is not None:
            assert abs(float(r["ours_text"]) - r["ours"]) <= 1e-5 * abs(r["ours"]) + 1e-300, r
print("json agrees with markdown")
PY
  then passed=$((passed+1)); else echo "FAIL paper.json against paper.md"; fail=$((fail+1)); fi
fi
finish
