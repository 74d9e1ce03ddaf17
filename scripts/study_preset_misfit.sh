#!/usr/bin/env bash
# Where the model test's misfit on the realistic preset's robots comes from:
# the same robots of scenarios/main.yaml (drawn geometry, the preset's
# effects: --keep-effects) calibrated with the preset as it is, with one of
# its effects off at a time, and built up from none of them (only Coulomb
# friction, then the transmission's compliance on every drive, on the
# torque-off joint's or on the driven ones', then viscous friction). Writes
# DIR/preset_misfit.md. A study already
# in DIR (its population.json) is kept: remove DIR to measure again.
#   bash scripts/study_preset_misfit.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/preset_misfit, 12 robots from seed 27000: about 6 minutes on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/preset_misfit}" "${2:-12}" "${3:-27000}"
effects=(compliance clearance coulomb viscous cyclic skew thermal)
declare -A off=([compliance]="transmission_compliance_rad_per_Nm: 0" [clearance]="passive_clearance_mm: 0"
                [coulomb]="coulomb_friction_Nm: 0" [viscous]="viscous_friction_Nm_s: 0" [cyclic]="encoder_cyclic_rad: 0"
                [skew]="encoder_skew_s: [0, 0, 0]" [thermal]="thermal: {rise_K: 0}")
# The preset's compliance (1e-4 rad/N m) on some drives only.
declare -A part=([compliance_j1]="transmission_compliance_rad_per_Nm: [1e-4, 0, 0]"
                 [compliance_j23]="transmission_compliance_rad_per_Nm: [0, 1e-4, 1e-4]")
# Each variant: the preset's effects it keeps ("all": every one; a partial
# compliance turns the rest of it off).
variants=(preset compliance clearance coulomb viscous cyclic skew thermal
          none only_coulomb coulomb_compliance coulomb_compliance_j1 coulomb_compliance_j23 coulomb_compliance_viscous)
declare -A keeps=([preset]=all [none]="" [only_coulomb]="coulomb" [coulomb_compliance]="coulomb compliance"
                  [coulomb_compliance_j1]="coulomb compliance_j1" [coulomb_compliance_j23]="coulomb compliance_j23"
                  [coulomb_compliance_viscous]="coulomb compliance viscous")
for e in "${effects[@]}"; do keeps[$e]="all but $e"; done
# The effects: keys of variant $1 after "preset: realistic".
variant_keys() {
  local keep=" ${keeps[$1]} " keys="" e
  for e in "${effects[@]}"; do
    if [[ $keep == " all "* ]]; then [[ $keep == *" but $e " ]] && keys+=", ${off[$e]}"
    elif [[ $keep == *" $e "* ]]; then :
    elif [[ $e == compliance && $keep =~ (compliance_j[0-9]+) ]]; then keys+=", ${part[${BASH_REMATCH[1]}]}"
    else keys+=", ${off[$e]}"; fi
  done
  echo "$keys"
}
for v in "${variants[@]}"; do
  f=$out/$v.yaml
  sed -e "s|^robot: .*|robot: $robot|" -e '/^expect:/,$d' \
      -e "s|^effects: .*|effects: {preset: realistic$(variant_keys "$v")}|" scenarios/main.yaml > "$f"
  study_population_of "$v" "$f" "study preset misfit: $v"
done
/usr/bin/python3 - "$out" "$count" "$first" "${variants[@]}" <<'PY'
import json, statistics, sys
out, count, first, variants = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
lines = [f"{count} robots of `scenarios/main.yaml` with the realistic preset's effects (seeds {first}..{first + count - 1}); "
         "`bash scripts/study_preset_misfit.sh`.", "",
         "| robots' effects | model test chi2/dof, median / worst | model test passes | positioning RMS, median / worst (um) |",
         "| --- | ---: | ---: | ---: |"]
for v in variants:
    p = json.load(open(f"{out}/{v}/population.json"))
    robots = [r for r in p["robots"] if r["failure"] is None]
    chi = [r["model_test"]["chi2_per_dof"] for r in robots]
    pos = [r["positioning_um"]["rms"] for r in robots]
    passed = sum(1 for r in robots if r["model_test"]["passed"])
    built = {"none": "none of the preset's effects", "only_coulomb": "only Coulomb friction",
             "coulomb_compliance": "Coulomb friction and compliance",
             "coulomb_compliance_j1": "Coulomb friction and compliance of joint 1 (torque-off)",
             "coulomb_compliance_j23": "Coulomb friction and compliance of joints 2, 3",
             "coulomb_compliance_viscous": "Coulomb and viscous friction and compliance"}
    label = "the preset" if v == "preset" else built.get(v, f"the preset, {v} off")
    lines.append(f"| {label} | {statistics.median(chi):.3f} / {max(chi):.3f} | {passed} of {len(robots)} | "
                 f"{statistics.median(pos):.1f} / {max(pos):.0f} |")
open(f"{out}/preset_misfit.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
