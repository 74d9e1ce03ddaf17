#!/usr/bin/env bash
# Whether a failed model test names the reading effect the calibration left
# out: the same robots of scenarios/main.yaml (drawn geometry, the realistic
# preset's effects: --keep-effects) calibrated as the main job does and with
# one reading effect left out of calibration.estimate at a time (the
# compliance takes its friction twist with it). Writes DIR/model_test_names.md.
# A study already in DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_model_test_names.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/model_test_names, 12 robots from seed 28400: about 2 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/model_test_names}" "${2:-12}" "${3:-28400}"
variants=(none compliance skew clearance)
# calibration.estimate of each variant (none: the main job's own, every effect
# on the fly and the clearance kept where the data show it).
declare -A estimate=([compliance]="skew, clearance" [skew]="compliance, friction, clearance"
                     [clearance]="compliance, skew, friction")
for v in "${variants[@]}"; do
  study_main_variant "model test names" preset "$v" "${estimate[$v]:+, estimate: [${estimate[$v]}]}"
done
/usr/bin/python3 - "$out" "$count" "$first" "${variants[@]}" <<'PY'
import collections, json, sys
out, count, first, variants = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
named = {"compliance": "transmission compliance", "skew": "the encoders' latch skew", "clearance": "joint clearance"}
lines = [f"{count} robots of `scenarios/main.yaml` with the realistic preset's effects (seeds {first}..{first + count - 1}); "
         "`bash scripts/study_model_test_names.sh`.", "",
         "| left out of the calibration | model test fails | names it first | names it | first named, most often |",
         "| --- | ---: | ---: | ---: | --- |"]
for v in variants:
    robots = [r for r in json.load(open(f"{out}/preset_{v}/population.json"))["robots"] if r["failure"] is None]
    failed = [r for r in robots if r["model_test"]["passed"] is False]
    calls = [r["model_test"].get("calls_for", []) for r in failed]
    want = named.get(v)
    first_n = sum(1 for c in calls if c and c[0] == want) if want else None
    any_n = sum(1 for c in calls if want in c) if want else None
    common = collections.Counter(c[0] if c else "none" for c in calls).most_common(1)
    label = "nothing" if v == "none" else v
    cell = lambda n: "-" if n is None else f"{n} of {len(failed)}"
    lines.append(f"| {label} | {len(failed)} of {len(robots)} | {cell(first_n)} | {cell(any_n)} | "
                 f"{common[0][0] + f' ({common[0][1]})' if common else '-'} |")
open(f"{out}/model_test_names.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
