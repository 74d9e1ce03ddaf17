#!/usr/bin/env bash
# What estimating the reducer's error once per joint revolution gives the
# main job (calibration.estimate's joint_error, on the fly by default;
# docs/MOTION_MODEL.md "The reducer's error once per joint revolution"): the
# same robots of scenarios/main.yaml (same seeds, same draws) calibrated with
#   carried:   estimate: [compliance, skew, friction, clearance, encoder_error]
#              (the default's other effects, listed: the error carried in the 1-sigma),
#   estimated: the same and joint_error (the default: estimated where the readings hold it),
# for three kinds of robot: the basic set of effects, the basic set with that
# error drawn, and every effect drawn. Writes DIR/joint_error.md and the table
# into docs/PROCEDURES.md between its joint-error markers. A study already in
# DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_joint_error.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/joint_error, 20 robots from seed 30400: about 10 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/joint_error}" "${2:-20}" "${3:-30400}"
kinds=(basic te_joint randomized)
listed="compliance, skew, friction, clearance, encoder_error"
study_kinds_before_after "joint error" carried ", estimate: [$listed]" estimated ", estimate: [$listed, joint_error]"
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import BOUND_COLUMN, MISFIT_COLUMN, before_after_table, write_between_markers
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lead = (f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); `bash scripts/study_joint_error.sh`. "
        "Before -> after: the reducer's error once per joint revolution carried (`calibration.estimate` without "
        "`joint_error`) -> estimated where the readings hold it (the default).")
table = "\n".join(before_after_table(out, kinds, "carried", "estimated", lead, [BOUND_COLUMN, MISFIT_COLUMN])) + "\n"
open(f"{out}/joint_error.md", "w").write(table)
write_between_markers("docs/PROCEDURES.md", "joint-error", table)
print(table)
PY
