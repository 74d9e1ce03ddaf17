#!/usr/bin/env bash
# The drift monitor on populations of robots (issue 31): every robot is
# calibrated as the main job, then monitors 45 s of operation with a 1e-4 rad
# slip of encoder 2 at 38 s (scenarios/monitor_population.yaml), through
# `gpm study population`, once without the monitor's learning phase
# (`monitor: {learning_s: 0}`: the stated reading model taken as exact, the
# monitor before issue 31) and once with it (the default). Populations: every
# effect drawn per chain (randomized) and, with PRESET=1, the realistic
# preset's effects (--keep-effects). Tabulates false alarms per hour of healthy
# monitored time (after learning, before the slip) and the slip's detection
# delay into DIR/monitor_population.md and .json, and writes the table into
# docs/MONITORING.md between its markers. VARIANTS="learning" and
# RUN_EFFECTS="preset" run only those populations (the table takes every
# population of the chosen effects found in DIR); VARIANTS=bigslip runs the
# population with a 1e-3 rad slip (learning on), VARIANTS=map the learning
# phase with its configuration map (`monitor: {map_radius_rad: 3e-3}`, off by
# default; its per-robot columns join the table); TABLE_ONLY=1 only tabulates.
# UNSEEN="4000,4001,..." also runs the randomized population on those seeds
# (robots the monitor was not tuned on: effects "unseen" in the tables);
# IDEAL=1 runs robots with no effect at all (`effects: ideal`, the monitor
# still told the data sheet: a robot better than its statement; effects
# "ideal"), each with its own geometry. UNSEEN_PRESET="6000,..." and
# UNSEEN_IDEAL="6000,..." run the preset and ideal robots of those seeds
# (geometries not tuned on: effects "unseen_preset", "unseen_ideal").
#   bash scripts/study_monitor_population.sh [DIR] [COUNT]
#   (default out/monitor_population, 10 robots a population; ~4 minutes a population on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/monitor_population}
count=${2:-10}
gpm=${GPM:-./build/app/gpm}
[[ -x $gpm ]] || bash scripts/build.sh
mkdir -p "$out"
scenario=scenarios/monitor_population.yaml
# The same scenario without learning (robot path made absolute: it lives in DIR).
robot=$(realpath models/gpm2002.yaml)
sed -e "s|^robot: .*|robot: $robot|" -e "s|^monitor: data_sheet.*|monitor: {preset: data_sheet, learning_s: 0}|" \
  "$scenario" > "$out/monitor_population_nolearning.yaml"
grep -q "learning_s: 0" "$out/monitor_population_nolearning.yaml"
# ... and with a slip ten times larger (1e-3 rad), for VARIANTS=bigslip.
sed -e "s|^robot: .*|robot: $robot|" -e "s|dth2: 1.0e-4|dth2: 1.0e-3|" "$scenario" > "$out/monitor_population_bigslip.yaml"
grep -q "dth2: 1.0e-3" "$out/monitor_population_bigslip.yaml"
# ... and with the learning phase's configuration map (calib/monitor/config_map.hpp), for VARIANTS=map.
sed -e "s|^robot: .*|robot: $robot|" -e "s|^monitor: data_sheet.*|monitor: {preset: data_sheet, map_radius_rad: 3.0e-3}|" \
  "$scenario" > "$out/monitor_population_map.yaml"
grep -q "map_radius_rad: 3.0e-3" "$out/monitor_population_map.yaml"
effects_list=(randomized); [[ ${PRESET:-0} == 1 ]] && effects_list+=(preset); [[ -n ${UNSEEN:-} ]] && effects_list+=(unseen)
[[ ${IDEAL:-0} == 1 ]] && effects_list+=(ideal)
[[ -n ${UNSEEN_PRESET:-} ]] && effects_list+=(unseen_preset); [[ -n ${UNSEEN_IDEAL:-} ]] && effects_list+=(unseen_ideal)
[[ ${TABLE_ONLY:-0} == 1 ]] && RUN_EFFECTS=" "  # TABLE_ONLY=1: tabulate what DIR holds
for effects in ${RUN_EFFECTS:-${effects_list[@]}}; do
  flag=(--count "$count"); [[ $effects == preset ]] && flag+=(--keep-effects)
  [[ $effects == unseen ]] && flag=(--seeds "$UNSEEN")
  [[ $effects == unseen_preset ]] && flag=(--seeds "$UNSEEN_PRESET" --keep-effects)
  for variant in ${VARIANTS:-nolearning learning}; do
    s=$scenario; [[ $variant != learning ]] && s=$out/monitor_population_$variant.yaml
    if [[ $effects == ideal || $effects == unseen_ideal ]]; then
      sed -e "s|^robot: .*|robot: $robot|" -e "s|^effects: realistic|effects: ideal|" "$s" > "$out/ideal_$variant.yaml"
      grep -q "^effects: ideal" "$out/ideal_$variant.yaml"
      s=$out/ideal_$variant.yaml flag=(--count "$count" --keep-effects)
      [[ $effects == unseen_ideal ]] && flag=(--seeds "$UNSEEN_IDEAL" --keep-effects)
    fi
    echo "study monitor population: $variant, $effects effects" >&2
    timeout 900 "$gpm" study population "$s" -o "$out/${variant}_$effects" "${flag[@]}" >/dev/null
  done
done
/usr/bin/python3 - "$out" "${effects_list[@]}" <<'PY'
import json, os, re, sys
out, effects_list = sys.argv[1], sys.argv[2:]
num = lambda v, f: "-" if v is None else format(v, f)
summary, per_robot, rows = [], [], []
label = {"nolearning": "without learning (before)", "learning": "with learning (after)",
         "bigslip": "with learning, slip 1e-3 rad", "map": "with learning and the configuration map"}
for effects in effects_list:
    pops = {}
    for variant in ("nolearning", "learning", "bigslip", "map"):
        p = os.path.join(out, f"{variant}_{effects}", "population.json")
        if os.path.exists(p):
            pops[variant] = json.load(open(p))
    for variant, pop in pops.items():
        s = pop["summary"]
        m = s.get("monitor", {})
        rows.append(dict(effects=effects, variant=variant, **s))
        summary.append(f"| {effects} | {label[variant]} | {s['robots']} ({s['failed']} failed) | "
                       f"{m.get('false_alarms', '-')} in {num(m.get('monitored_hours'), '.3f')} h | "
                       f"{num(m.get('false_alarms_per_hour'), '.0f')} | {m.get('robots_with_false_alarms', '-')} | "
                       f"{m.get('detected', '-')} of {m.get('events', '-')} | "
                       f"{num(m.get('detection_delay_median_s'), '.3f')} / {num(m.get('detection_delay_max_s'), '.3f')} |")
    if "nolearning" in pops and "learning" in pops:
        before = {r["seed"]: r for r in pops["nolearning"]["robots"]}
        mapped = {r["seed"]: r for r in pops["map"]["robots"]} if "map" in pops else {}
        for r in pops["learning"]["robots"]:
            b = before.get(r["seed"], {})
            def cells(x):
                mon = x.get("monitor")
                if not mon:
                    return ["failed" if x.get("failure") else "-", "-", "-"]
                d = mon["detection_delay_s"]
                named = re.search(r"\((\w+) ", mon["detection"] or "")
                return [f"{mon['false_alarms']} ({num(mon['false_alarms_per_hour'], '.0f')}/h)",
                        "missed" if d is None else f"{d:.3f} s ({named.group(1) if named else '?'})",
                        num(mon.get("learned_scale"), ".2f")]
            cb, ca, cm = cells(b), cells(r), cells(mapped.get(r["seed"], {}))
            per_robot.append(f"| {effects} | {r['seed']} | {cb[0]} | {cb[1]} | {ca[0]} | {ca[1]} | {ca[2]} | "
                             f"{cm[0]} | {cm[1]} | {cm[2]} |")
md = ["| effects | monitor | robots | false alarms (healthy time after learning) | per hour | robots with any | "
      "slip detected | delay median / worst (s) |",
      "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"] + summary + ["",
      "Per robot (false alarms in the healthy time, per hour; slip detection delay and the parameter it was "
      "named as; the innovation scale learnt, 1 = as stated; map: with the configuration map, - when not run):", "",
      "| effects | seed | before: false alarms | before: slip | after: false alarms | after: slip | learnt scale | "
      "map: false alarms | map: slip | map: learnt scale |",
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"] + per_robot
text = "\n".join(md) + "\n"
open(os.path.join(out, "monitor_population.md"), "w").write(text)
json.dump(rows, open(os.path.join(out, "monitor_population.json"), "w"), indent=2)
doc = "docs/MONITORING.md"
d = open(doc).read()
begin, end = "<!-- monitor_population: begin (scripts/study_monitor_population.sh) -->", "<!-- monitor_population: end -->"
if begin in d and end in d:
    d = d[:d.index(begin) + len(begin)] + "\n" + text + d[d.index(end):]
    open(doc, "w").write(d)
print(text)
PY
