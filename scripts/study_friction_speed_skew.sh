#!/usr/bin/env bash
# What leaving out the friction speeds the latch skew takes up gives the main
# job (calibration.drive_friction.max_skew_correlation, docs/PROCEDURES.md
# "The friction's speed and the latch skew"): the same robots of
# scenarios/main.yaml (same seeds, same draws) calibrated with every speed of
# the grid tried (max_skew_correlation: 1, the calibration before) and with
# the default (a speed is tried only where its friction twist correlates with
# the joint speed at most 0.949 over the samples), for four kinds of robot:
# the basic set of effects, the basic set with the backlash drawn, every
# effect drawn and the realistic preset's. Writes DIR/speed-skew.md
# and the table into docs/PROCEDURES.md between its speed-skew markers. A
# study already in DIR (its population.json) is kept: remove DIR to measure
# again.
#   bash scripts/study_friction_speed_skew.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/friction_speed_skew, 20 robots from seed 30900)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/friction_speed_skew}" "${2:-20}" "${3:-30900}"
kinds=(basic backlash randomized preset)
study_kinds_before_after "friction speed" every ", drive_friction: {max_skew_correlation: 1}" told ""
lead="$count robots of \`scenarios/main.yaml\` each (seeds $first..$((first + count - 1))); \
\`bash scripts/study_friction_speed_skew.sh\`. Before -> after: every friction speed of the grid tried -> \
those whose twist the joints' speeds tell from the latch skew (\`calibration.drive_friction.max_skew_correlation\`)."
/usr/bin/python3 scripts/population_pair.py "$out" every told speed-skew "$lead" "${kinds[@]}"
