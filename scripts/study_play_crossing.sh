#!/usr/bin/env bash
# What leaving out the samples of a passive link crossing its play gives the
# main job (calibration.crossing_s, calib/play_crossing.hpp): the same robots
# of scenarios/main.yaml (same seeds, same draws) calibrated with
#   kept:    crossing_s 0 (every sample whose force signs are certain used),
#   crossed: the default (the samples of the 20 ms after a link's force
#            changed sign left out, where the model fits within chi2/dof 2),
# for three kinds of robot: the basic set of effects, every effect drawn and
# the realistic preset's. Writes DIR/play_crossing.md and the table into
# docs/PROCEDURES.md between its play-crossing markers. A study already in
# DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_play_crossing.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/play_crossing, 30 robots from seed 29000: about 10 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/play_crossing}" "${2:-30}" "${3:-29000}"
kinds=(basic randomized preset)
for kind in "${kinds[@]}"; do
  study_main_variant "play crossing" "$kind" kept ", crossing_s: 0"
  study_main_variant "play crossing" "$kind" crossed ""
done
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import BOUND_COLUMN, MISFIT_COLUMN, before_after_table, write_between_markers
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lead = (f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); "
        "`bash scripts/study_play_crossing.sh`. Before -> after: `calibration.crossing_s` 0 -> the default, 0.02 s.")
table = "\n".join(before_after_table(out, kinds, "kept", "crossed", lead, [BOUND_COLUMN, MISFIT_COLUMN])) + "\n"
open(f"{out}/play_crossing.md", "w").write(table)
write_between_markers("docs/PROCEDURES.md", "play-crossing", table)
print(table)
PY
