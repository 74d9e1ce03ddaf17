#!/usr/bin/env bash
# What an alternating preload of the redundant joint gives the main job: the
# same robots of scenarios/main.yaml (same seeds, same draws) sampled with
# joint 1 torque-off (the main job) and with joint 1 pushing TORQUE N m one way,
# then the other, every ALTERNATE_S seconds (servo.modes [{torque: -TORQUE,
# alternate_s: ALTERNATE_S}, position, position]: each flank of its reducer and
# each end of every passive link's play taken up in turn), for three kinds of
# robot: the basic set of effects, every effect drawn and the realistic
# preset's effects with drawn geometry. Writes DIR/alternating_preload.md. A
# study already in DIR (its population.json) is kept: remove DIR to measure
# again.
#   bash scripts/study_alternating_preload.sh [DIR] [COUNT] [FIRST_SEED] [TORQUE] [ALTERNATE_S]
#   (default out/alternating_preload, 30 robots from seed 28720, 2 N m every
#   1.2 s: about 10 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/alternating_preload}" "${2:-30}" "${3:-28720}"
torque=${4:-2} alternate=${5:-1.2}
kinds=(basic randomized preset)
for kind in "${kinds[@]}"; do
  for variant in torque_off alternating; do
    f=$out/${kind}_$variant.yaml
    sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: .*|effects: ${kind_effects[$kind]}|" -e '/^expect:/,$d' \
        scenarios/main.yaml > "$f"
    if [[ $variant == alternating ]]; then
      sed -i "s|modes: \[torque_off, |modes: [{torque: -$torque, alternate_s: $alternate}, |" "$f"
      grep -qF "alternate_s: $alternate}" "$f"
    fi
    study_population_of "${kind}_$variant" "$f" "study alternating preload: $kind effects, $variant"
  done
done
/usr/bin/python3 - "$out" "$count" "$first" "$torque" "$alternate" "${kinds[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts")
from population_pair import before_after_table
out, count, first, torque, alternate = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
lines = before_after_table(out, sys.argv[6:], "torque_off", "alternating",
                           f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); "
                           "`bash scripts/study_alternating_preload.sh`. Before -> after: joint 1 torque-off (the "
                           f"main job) -> joint 1 pushing {torque} N m, its sign changed every {alternate} s.")
open(f"{out}/alternating_preload.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
