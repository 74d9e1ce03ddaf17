# The twin's effects beyond its basic set (geometry, compliance and stiffness
# bands, passive clearance, drive friction, masses, thermal growth, the
# encoders' own errors and latch skew), each as the `effects:` key that turns
# it off; sourced by scripts/study_effect_budget.sh and
# scripts/study_friction_balance.sh, which start from `preset: randomized`.
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
