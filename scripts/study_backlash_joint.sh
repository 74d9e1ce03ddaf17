#!/usr/bin/env bash
# Which joint's backlash costs the main job's calibration its accuracy: robots
# of scenarios/main.yaml with the twin's basic set drawn (every effect beyond
# it off, scripts/effects_beyond_basic.sh) and one lost motion B on one joint
# at a time (joint 1 is the main job's torque-off joint), and on none. Each
# row is one `gpm study population --keep-effects` run over the same robots;
# the table (median and worst positioning RMS, median chi2/dof of the model
# test) goes to DIR/backlash_joint.md.
#   bash scripts/study_backlash_joint.sh [DIR] [COUNT] [FIRST_SEED] [B_RAD]
#   (default out/backlash_joint, 20 robots from seed 26000, B = 2.1e-3 rad:
#   7 arcmin, within the twin's draw of 0.3-10 arcmin; about 2 minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/backlash_joint}" "${2:-20}" "${3:-26000}"
b=${4:-2.1e-3}
basic=$(all_off_but none | sed 's/backlash_rad: 0, //')

# Runs row $1 with the backlash list $2.
row() {
  local name=$1 f=$out/$1.yaml
  sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: .*|effects: {preset: randomized, $basic, backlash_rad: $2}|" \
      -e '/^expect:/,$d' scenarios/main.yaml > "$f"
  "$gpm" study population "$f" --keep-effects --seeds "$seeds" -o "$out/$name" --progress none > "$out/$name.log" 2>&1
  python3 - "$out/$name/population.json" "$name" "$2" <<'EOF'
import json, statistics, sys
robots = json.load(open(sys.argv[1]))["robots"]
rms = [r["positioning_um"]["rms"] for r in robots if r.get("positioning_um")]
chi = [r["model_test"]["chi2_per_dof"] for r in robots if r.get("model_test")]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {statistics.median(rms):.1f} | {max(rms):.0f} | "
      f"{statistics.median(chi):.1f} | {len(rms)} |")
EOF
}
{
  echo "$count robots of \`scenarios/main.yaml\` (seeds $first..$((first + count - 1))), the basic set drawn; \`bash scripts/study_backlash_joint.sh\`."
  echo
  echo "| backlash | backlash_rad | positioning RMS, median (um) | worst robot (um) | model test chi2/dof (median) | calibrated |"
  echo "| --- | --- | ---: | ---: | ---: | ---: |"
  row none "[0, 0, 0]"
  row joint1 "[$b, 0, 0]"
  row joint2 "[0, $b, 0]"
  row joint3 "[0, 0, $b]"
} | tee "$out/backlash_joint.md"
