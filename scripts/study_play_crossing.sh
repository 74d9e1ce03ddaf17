#!/usr/bin/env bash
# What leaving out the samples of a passive link crossing its play gives the
# main job (calibration.crossing_s, calib/play_crossing.hpp): the same robots
# of scenarios/main.yaml (same seeds, same draws) calibrated with
#   kept:    crossing_s 0 (every sample whose force signs are certain used),
#   crossed: the default (the samples of the 20 ms after a link's force
#            changed sign left out, where the model fits within chi2/dof 2),
# for three kinds of robot: the basic set of effects, every effect drawn and
# the realistic preset's. Writes DIR/play-crossing.md and the table into
# docs/PROCEDURES.md between its play-crossing markers. A study already in
# DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_play_crossing.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/play_crossing, 30 robots from seed 29000: about 10 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/play_crossing}" "${2:-30}" "${3:-29000}"
kinds=(basic randomized preset)
study_kinds_before_after "play crossing" kept ", crossing_s: 0" crossed ""
/usr/bin/python3 scripts/population_pair.py "$out" kept crossed play-crossing \
  "$count robots of \`scenarios/main.yaml\` each (seeds $first..$((first + count - 1))); \`bash scripts/study_play_crossing.sh\`. Before -> after: \`calibration.crossing_s\` 0 -> the default, 0.02 s." \
  "${kinds[@]}"
