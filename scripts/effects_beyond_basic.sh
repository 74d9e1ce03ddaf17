# The twin's effects beyond its basic set (geometry, compliance and stiffness
# bands, passive clearance, drive friction, masses, thermal growth, the
# encoders' own errors and latch skew), each as the `effects:` key that turns
# it off; sourced by scripts/study_effect_budget.sh,
# scripts/study_friction_balance.sh, scripts/study_force_sign.sh,
# scripts/study_backlash_joint.sh, scripts/study_preset_misfit.sh,
# scripts/study_model_test_names.sh, scripts/study_alternating_preload.sh,
# scripts/study_positioning_design.sh and scripts/study_joint_error.sh
# (study_setup for their inputs; the first four start from `preset: randomized`).
names=(backlash hysteresis te_joint te_motor stiction load_friction torque_constant cogging hub_pins jitter)
declare -A off=(
  [backlash]="backlash_rad: 0"
  [hysteresis]="drive_hysteresis_rad: 0"
  [te_joint]="transmission_error_joint_rad: 0"
  [te_motor]="transmission_error_motor_rad: 0"
  [stiction]="stiction_excess_Nm: 0"
  [load_friction]="friction_load_coefficient: 0"
  [torque_constant]="torque_constant_delta: 0"
  [cogging]="cogging_Nm: 0"
  [hub_pins]="hub_pin_offset_um: [[0, 0], [0, 0], [0, 0]]"
  [jitter]="encoder_jitter_s: 0"
)
# The keys that turn off every named effect except $1 (none: all of them).
all_off_but() {
  local keys="" n
  for n in "${names[@]}"; do [[ $n == "$1" ]] || keys+="${keys:+, }${off[$n]}"; done
  echo "$keys"
}

# The study's inputs: gpm (GPM, else ./build/app/gpm, built if missing), the
# output folder out=$1 (made), count=$2 robots from seed first=$3 (seeds, a
# comma-separated list) and the robot file (robot, an absolute path).
study_setup() {
  out=$1 count=$2 first=$3
  gpm=${GPM:-./build/app/gpm}
  [[ -x $gpm ]] || bash scripts/build.sh
  mkdir -p "$out"
  seeds=$(seq -s, "$first" $((first + count - 1)))
  robot=$(realpath models/gpm2002.yaml)
}

# The kinds of robot the before/after studies compare on: the basic set
# (every effect above off), every effect drawn, the realistic preset's, and
# the basic set with the backlash, the reducer's error once per joint
# revolution or the motors' cogging drawn.
declare -A kind_effects=([basic]="{preset: randomized, $(all_off_but none)}" [randomized]="randomized" [preset]="realistic"
                        [backlash]="{preset: randomized, $(all_off_but backlash)}"
                        [te_joint]="{preset: randomized, $(all_off_but te_joint)}"
                        [cogging]="{preset: randomized, $(all_off_but cogging)}")

# The robots of kind $2 (kind_effects) calibrated by scenarios/main.yaml with
# ", ..." $4 appended to its calibration map (and $5, when given, to its
# sampling map), into $out/$2_$3 (study_setup's inputs; kept when its
# population.json is there); $1 names the study.
study_main_variant() {
  local study=$1 kind=$2 variant=$3 extra=$4 sampling=${5:-}
  local f=$out/${kind}_$variant.yaml
  sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: .*|effects: ${kind_effects[$kind]}|" -e '/^expect:/,$d' \
      -e "s|^calibration: {\(.*\)}$|calibration: {\1$extra}|" \
      -e "s|^sampling: {\(.*\)}$|sampling: {\1$sampling}|" scenarios/main.yaml > "$f"
  [[ -z $extra ]] || grep -qF "${extra#, }" "$f"
  [[ -z $sampling ]] || grep -qF "${sampling#, }" "$f"
  study_population_of "${kind}_$variant" "$f" "study $study: $kind effects, $variant"
}

# The robots of scenario file $2 (their effects kept) into $out/$1 (kept
# when its population.json is there); $3 says so on stderr.
study_population_of() {
  [[ -f $out/$1/population.json ]] && return
  echo "$3" >&2
  "$gpm" study population "$2" --keep-effects --seeds "$seeds" -o "$out/$1" --progress none > "$out/$1.log"
}

# The robots of every kind in kinds (kind_effects) calibrated as $2 with
# ", ..." $3 appended to the calibration map, then as $4 with $5 appended
# (and $6, $7, when given, to the sampling map of each; study_main_variant's
# variants, into $out); $1 names the study.
study_kinds_before_after() {
  local kind
  for kind in "${kinds[@]}"; do
    study_main_variant "$1" "$kind" "$2" "$3" "${6:-}"
    study_main_variant "$1" "$kind" "$4" "$5" "${7:-}"
  done
}
