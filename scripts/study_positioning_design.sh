#!/usr/bin/env bash
# What designing the main job's poses for the positioning, with the encoders'
# own error once per joint revolution estimated under the data sheet's prior,
# gives (calib/excitation/positioning_design.hpp, sampling.criterion,
# calibration.estimate's encoder_error): the same robots of
# scenarios/main.yaml (same seeds, same draws) calibrated with
#   worst:       sampling.criterion worst, the error carried (calibration.estimate
#                listing the four other effects): the procedure before;
#   positioning: the defaults (poses for the positioning, the error estimated
#                where the encoders turn with the joints),
# for three kinds of robot: the basic set of effects, every effect drawn and
# the realistic preset's. Writes DIR/positioning-design.md and the table into
# docs/PROCEDURES.md between its positioning-design markers. A study already
# in DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_positioning_design.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/positioning_design, 30 robots from seed 30100: about 12 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/positioning_design}" "${2:-30}" "${3:-30100}"
kinds=(basic randomized preset)
study_kinds_before_after "positioning design" worst ", estimate: [compliance, skew, friction, clearance]" \
  positioning "" ", criterion: worst" ""
/usr/bin/python3 scripts/population_pair.py "$out" worst positioning positioning-design \
  "$count robots of \`scenarios/main.yaml\` each (seeds $first..$((first + count - 1))); \`bash scripts/study_positioning_design.sh\`. Before -> after: poses for the worst parameter with the encoders' error once per joint revolution carried -> poses for the positioning with it estimated (the defaults)." \
  "${kinds[@]}"
