#!/usr/bin/env bash
# What the passive links' force-sign threshold from the hub's force balance
# gives the main job: the same robots of scenarios/main.yaml (same seeds, same
# draws) calibrated with calibration.tension_min_N stated at 1.5 N (the one
# threshold of before) and with the default (twice a link's force 1-sigma as
# the balance sees it), for three kinds of robot: the basic set of effects
# (as scripts/study_effect_budget.sh's "basic set only"), every effect drawn
# (effects: randomized) and the realistic preset's effects with drawn
# geometry. Writes DIR/force_sign.md. A study already in DIR (its
# population.json) is kept: remove DIR to measure again.
#   bash scripts/study_force_sign.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/force_sign, 20 robots from seed 27100: about 5 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/force_sign}" "${2:-20}" "${3:-27100}"
kinds=(basic randomized preset)
study_kinds_before_after "force sign" stated ", tension_min_N: 1.5" balance ""
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import before_after_table
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lines = before_after_table(out, kinds, "stated", "balance",
                           f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); "
                           "`bash scripts/study_force_sign.sh`. Before -> after: `tension_min_N: 1.5` stated -> the "
                           "default (twice a link's force 1-sigma by the hub's force balance).")
open(f"{out}/force_sign.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
