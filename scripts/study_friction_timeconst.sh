#!/usr/bin/env bash
# What the twin's friction law and the drives' velocity loop do to the main
# job: the same robots of scenarios/main.yaml (same seeds, same draws) on the
# twin of before (the drives' friction MuJoCo's soft row at its default time
# constant, `effects: {friction_timeconst_s: 0.02}`: below F a drive creeps,
# a coasting rotor slows over about 10 ms; P/P drives, `servo: {ki: 0}`) and
# of now (the friction as stiff as the physics step allows, near hard Coulomb
# friction; the main job's PI velocity loop), for four kinds of robot: the
# basic set of effects, the basic set with the backlash drawn, every effect
# drawn and the realistic preset's. The calibration is the same in both:
# only the twin and its drives differ.
# Writes DIR/friction_timeconst.md and the table into docs/PROCEDURES.md
# between its friction-timeconst markers. A study already in DIR (its
# population.json) is kept: remove DIR to measure again.
#   bash scripts/study_friction_timeconst.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/friction_timeconst, 20 robots from seed 29620: about 12
#   minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/friction_timeconst}" "${2:-20}" "${3:-29620}"
kinds=(basic backlash randomized preset)
for kind in "${kinds[@]}"; do
  effects=${kind_effects[$kind]}
  [[ $effects == \{* ]] || effects="{preset: $effects}"
  for variant in soft stiff; do
    f=$out/${kind}_$variant.yaml
    fx=$effects ki='ki: 500'
    [[ $variant == stiff ]] || fx="${effects%\}}, friction_timeconst_s: 0.02}" ki='ki: 0'
    sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: .*|effects: $fx|" -e "s|^\(servo: {.*\)ki: 500|\1$ki|" \
        -e '/^expect:/,$d' scenarios/main.yaml > "$f"
    grep -q "^servo: {.*$ki" "$f"
    [[ $variant == stiff ]] || grep -q "friction_timeconst_s: 0.02}$" "$f"
    study_population_of "${kind}_$variant" "$f" "study friction time constant: $kind effects, $variant"
  done
done
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import BOUND_COLUMN, before_after_table, write_between_markers
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lines = before_after_table(out, kinds, "soft", "stiff",
                           f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); "
                           "`bash scripts/study_friction_timeconst.sh`. Soft -> stiff: the drives' friction at MuJoCo's "
                           "default time constant (`friction_timeconst_s: 0.02`) and P/P drives (`servo: {ki: 0}`) -> "
                           "the twin's friction at two physics steps and the main job's PI velocity loop; the "
                           "calibration the same.", [BOUND_COLUMN])
table = "\n".join(lines) + "\n"
open(f"{out}/friction_timeconst.md", "w").write(table)
write_between_markers("docs/PROCEDURES.md", "friction-timeconst", table)
print(table)
PY
