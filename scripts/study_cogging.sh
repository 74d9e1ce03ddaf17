#!/usr/bin/env bash
# What the motors' cogging in the calibration gives the main job (docs/
# MOTION_MODEL.md "The motors' cogging"): the same robots of
# scenarios/main.yaml (same seeds, same draws) calibrated with the robot
# file's data sheet stating no cogging periods (cogging_periods: 0, the
# calibration before it knew the cogging) and stating the GPM2002's 24 (the
# cogging torque from the hub's force balance added to the drive torques,
# the twist's harmonic a candidate of the reading model), for four kinds of
# robot: the basic set of effects, the basic set with the cogging drawn,
# every effect drawn and the realistic preset's. Writes DIR/cogging.md and
# the table into docs/PROCEDURES.md between its cogging markers. A study
# already in DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_cogging.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/cogging, 20 robots from seed 30600: about 12 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/cogging}" "${2:-20}" "${3:-30600}"
stated=$robot
unstated=$(realpath "$out")/gpm2002_no_cogging.yaml
sed -e 's/^  cogging_periods: 24 /  cogging_periods: 0  /' "$stated" > "$unstated"
grep -q '^  cogging_periods: 0 ' "$unstated"
kinds=(basic cogging randomized preset)
for kind in "${kinds[@]}"; do
  robot=$unstated study_main_variant cogging "$kind" unstated ""
  robot=$stated study_main_variant cogging "$kind" stated ""
done
lead="$count robots of \`scenarios/main.yaml\` each (seeds $first..$((first + count - 1))); \`bash scripts/study_cogging.sh\`. \
Before -> after: the data sheet states no cogging periods -> the GPM2002's 24 per motor revolution \
(\`data_sheet.cogging_periods\`)."
/usr/bin/python3 scripts/population_pair.py "$out" unstated stated cogging "$lead" "${kinds[@]}"
