#!/usr/bin/env bash
# What each drive's friction from the hub's force balance gives the main job:
# the same robots of scenarios/main.yaml (same seeds, same draws) calibrated
# with calibration.drive_friction.from_balance false (the data sheet's one
# value, scaled by the model test) and true (the default), for three kinds of
# robot: the basic set of effects (every drive-train and motor-encoder effect
# beyond it off, as scripts/study_effect_budget.sh's "basic set only"), every
# effect drawn (effects: randomized) and the realistic preset's effects with
# drawn geometry. Also how far the balance's friction lies from each robot's
# (population.json: friction_balance against effects). Writes
# DIR/friction_balance.md. A study already in DIR (its population.json) is
# kept: remove DIR to measure again.
#   bash scripts/study_friction_balance.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/friction_balance, 20 robots from seed 20000: about 5 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/friction_balance}" "${2:-20}" "${3:-20000}"
kinds=(basic randomized preset)
for kind in "${kinds[@]}"; do
  for balance in false true; do
    study_main_variant "friction balance" "$kind" "$balance" ", drive_friction: {from_balance: $balance}"
  done
done
/usr/bin/python3 - "$out" "$count" "$first" "${kinds[@]}" <<'PY'
import statistics, sys
sys.path.insert(0, "scripts")
from population_pair import KIND_LABEL, before_after, load_pair
out, count, first, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
MODEL_DAMPING = 0.05  # N m s/rad the model has before the effects' viscous friction (sim MjcfOptions)
lines = [f"{count} robots of `scenarios/main.yaml` each (seeds {first}..{first + count - 1}); "
         "`bash scripts/study_friction_balance.sh`. Before -> after: `drive_friction.from_balance` false -> true.", "",
         "| robots' effects | positioning RMS median (um) | worst robot (um) | parameters within 3 sigma | worst parameter (sigma) | "
         "robots better / worse | Coulomb friction error, median / worst (N m): data sheet -> balance | "
         "viscous friction error (N m s/rad), likewise |",
         "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
for kind in kinds:
    a, b = load_pair(out, kind, "false", "true")
    c = before_after(a, b)
    def errors(key, truth_key, stated, offset):
        sheet, found = [], []
        for r in b["robots"]:
            truth = [t + offset for t in r["effects"][truth_key]]
            sheet += [abs(stated - t) for t in truth]
            if "friction_balance" in r:
                found += [abs(f - t) for f, t in zip(r["friction_balance"][key], truth)]
        return (f"{statistics.median(sheet):.3f} / {max(sheet):.2f} -> {statistics.median(found):.3f} / {max(found):.2f}"
                if found else "-")
    fr = errors("coulomb_Nm", "coulomb_friction_Nm", 0.3, 0.0) + " | " + \
         errors("viscous_Nm_s", "viscous_friction_Nm_s", 0.15, MODEL_DAMPING)
    lines.append(f"| {KIND_LABEL[kind]} | {c['median']} | {c['worst']} | {c['within']} | {c['worst_sigma']} | "
                 f"{c['better_worse']} | {fr} |")
open(f"{out}/friction_balance.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
