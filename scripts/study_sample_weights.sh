#!/usr/bin/env bash
# What weighing the samples the friction leaves uncertain gives the main job
# (calib/sample_weights.hpp): the same robots of scenarios/main.yaml (same
# seeds, same draws) calibrated with calibration.drive_friction
#   none:  weigh_rest and weigh_signs false (every sample weighs 1),
#   rest:  weigh_rest true, the default (a sample with some joint slower
#          than a reading step per sample weighs as its friction twist, known
#          within +-c F only, allows),
#   signs: weigh_rest and weigh_signs true (also a force sign its doubt
#          leaves uncertain, where the model fits within chi2/dof 2),
# for four kinds of robot: the basic set of effects, the basic set with the
# backlash drawn, every effect drawn and the realistic preset's. Writes
# DIR/sample_weights.md and the tables into docs/PROCEDURES.md between its
# sample-weights markers. A study already in DIR (its population.json) is
# kept: remove DIR to measure again.
#   bash scripts/study_sample_weights.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/sample_weights, 20 robots from seed 29700: about 20 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/sample_weights}" "${2:-20}" "${3:-29700}"
kinds=(basic backlash randomized preset)
declare -A keys=([none]="weigh_rest: false, weigh_signs: false" [rest]="weigh_rest: true, weigh_signs: false"
                 [signs]="weigh_rest: true, weigh_signs: true")
for kind in "${kinds[@]}"; do
  for variant in none rest signs; do
    study_main_variant "sample weights" "$kind" "$variant" ", drive_friction: {${keys[$variant]}}"
  done
done
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import BOUND_COLUMN, MISFIT_COLUMN, before_after_table, write_between_markers
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lead = f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); `bash scripts/study_sample_weights.sh`."
rest = before_after_table(out, kinds, "none", "rest", lead + " Before -> after: `drive_friction.weigh_rest` false -> "
                          "true (`weigh_signs` false; the default weighs the rest, not the signs; the model test judges the residuals "
                          "unweighted).", [BOUND_COLUMN, MISFIT_COLUMN])
signs = before_after_table(out, kinds, "rest", "signs", "The same robots, before -> after: `weigh_signs` false -> true "
                           "(`weigh_rest` true).", [BOUND_COLUMN, MISFIT_COLUMN])
table = "\n".join(rest) + "\n\n" + "\n".join(signs) + "\n"
open(f"{out}/sample_weights.md", "w").write(table)
write_between_markers("docs/PROCEDURES.md", "sample-weights", table)
print(table)
PY
