#!/usr/bin/env bash
# Which effects of a real robot cost the main job's calibration its accuracy:
# the population of scenarios/main.yaml (every effect drawn per chain,
# `effects: randomized`), then the same robots (same seeds, the other draws
# unchanged) with one effect beyond the twin's basic set set to 0, with all
# of them set to 0, and with only one of them. The basic set stays drawn in
# every row: geometry, compliance, passive clearance, drive friction,
# masses, thermal growth, the encoders' own errors and latch skew, stiffness
# bands. Each row is one `gpm study population --keep-effects` run; the table
# (median and worst positioning RMS over the robots, error over the stated
# 1-sigma, worst parameter in its 1-sigma) goes to DIR/effect_budget.md and
# into docs/PROCEDURES.md between its effect-budget markers.
#   bash scripts/study_effect_budget.sh [DIR] [COUNT] [FIRST_SEED]
#   (default out/effect_budget, 10 robots a row from seed 2026: 22 rows;
#   20 robots a row took 52 minutes on 2 cores shared with other runs).
# The last column compares each robot with itself in the row it changes.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/effects_beyond_basic.sh
study_setup "${1:-out/effect_budget}" "${2:-10}" "${3:-2026}"

# Runs row $1 with the effects keys $2 (after `preset: randomized`); a row
# whose population.json is in DIR is kept (a study stopped part way resumes).
row() {
  local name=$1 keys=$2 f=$out/$1.yaml
  sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: .*|effects: {preset: randomized${keys:+, $keys}}|" \
      -e '/^expect:/,$d' scenarios/main.yaml > "$f"
  grep -q "^effects: {preset: randomized" "$f"
  [[ -f $out/$name/population.json ]] ||
    "$gpm" study population "$f" --keep-effects --seeds "$seeds" -o "$out/$name" --progress none > "$out/$name.log" 2>&1
  echo "$name: $(sed -n 3p "$out/$name/population.md" | cut -c3-160)"
}
row all ""
for n in "${names[@]}"; do row "without_$n" "${off[$n]}"; done
row basic "$(all_off_but none)"
for n in "${names[@]}"; do row "only_$n" "$(all_off_but "$n")"; done

python3 - "$out" "$count" "$first" "${names[@]}" <<'EOF'
import json, math, sys
sys.path.insert(0, 'scripts')
from population_pair import positioning_by_seed, write_between_markers
out, count, first, names = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
label = {'backlash': 'backlash', 'hysteresis': 'drive hysteresis', 'te_joint': 'transmission error per joint revolution',
         'te_motor': 'transmission error per motor revolution', 'stiction': 'stiction', 'load_friction': 'load friction',
         'torque_constant': 'torque constant', 'cogging': 'cogging', 'hub_pins': 'hub pin offsets', 'jitter': 'latch jitter'}
def positioning(row):
    return positioning_by_seed(json.load(open(f'{out}/{row}/population.json')))
# Robot by robot against the row `against` (the same seeds): the geometric
# mean of this row's positioning RMS over that row's, and its range (a
# median over 20 robots moves by 10 um from one draw to another; the same
# robot's ratio shows what the effect does to it).
def ratio(row, against):
    a, b = positioning(row), positioning(against)
    r = [a[s] / b[s] for s in a if s in b and b[s] > 0]
    if not r: return "-"
    return f"{math.exp(sum(map(math.log, r)) / len(r)):.2f} ({min(r):.2f}-{max(r):.2f})"
def cells(row, against=None):
    s = json.load(open(f'{out}/{row}/population.json'))['summary']
    ok = s['robots'] - s['failed']
    return (f"{s['positioning_median_um']:.1f} | {s['positioning_max_um']:.0f} | "
            f"{s['normalised_positioning_median']:.2f} | {s['worst_sigma_ratio']:.1f} | {ok} | "
            f"{ratio(row, against) if against else '-'}")
lines = [f"{count} robots of `scenarios/main.yaml` (seeds {first}..{first + count - 1}), each row the same robots; "
         "`bash scripts/study_effect_budget.sh`.", "",
         "| robots | positioning RMS, median (um) | worst robot (um) | error / stated 1-sigma (median) | worst parameter (sigma) | calibrated "
         "| per robot against the row it changes: geometric mean of the ratio (range) |",
         "| --- | ---: | ---: | ---: | ---: | ---: | ---: |",
         f"| every effect drawn | {cells('all')} |"]
lines += [f"| every effect but {label[n]} | {cells('without_' + n, 'all')} |" for n in names]
lines += [f"| the basic set only (none of the above) | {cells('basic')} |"]
lines += [f"| the basic set and {label[n]} | {cells('only_' + n, 'basic')} |" for n in names]
table = "\n".join(lines) + "\n"
open(f'{out}/effect_budget.md', 'w').write(table)
write_between_markers('docs/PROCEDURES.md', 'effect-budget', table)
print(table)
EOF
