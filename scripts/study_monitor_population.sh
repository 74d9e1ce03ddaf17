#!/usr/bin/env bash
# The drift monitor on populations of robots (issue 31): every robot is
# calibrated as the main job, then monitors 45 s of operation with a 1e-4 rad
# slip of encoder 2 at 38 s (scenarios/monitor_population.yaml), through
# `gpm study population`, in variants of the monitor (VARIANTS, default
# "nolearning nomap learning"): nolearning (`monitor: {learning_s: 0}`: the
# stated reading model taken as exact), nomap (the learning phase without its
# configuration map, `map_radius_rad: 0`), learning (the default monitor:
# learning phase and configuration map); slip1 and slip3 are the default
# monitor with the slip on encoder 1 or 3 instead, bigslip with a 1e-3 rad
# slip. Populations: every effect drawn per chain (randomized, seeds
# 2026..) and, with PRESET=1, the realistic preset's effects
# (--keep-effects). Tabulates false alarms per hour of healthy monitored
# time (after learning, before the slip) and the slip's detection delay into
# DIR/monitor_population.md and .json, and writes the table into
# docs/MONITORING.md between its markers. RUN_EFFECTS="preset" runs only
# those populations (the table takes every population of the chosen effects
# found in DIR); TABLE_ONLY=1 only tabulates. UNSEEN="8000,8001,..." also runs
# the randomized population on those seeds (robots the monitor was not tuned
# on: effects "unseen"); IDEAL=1 runs robots with no effect at all
# (`effects: ideal`, the monitor still told the data sheet: a robot better
# than its statement; effects "ideal"), each with its own geometry.
# UNSEEN_PRESET="8000,..." and UNSEEN_IDEAL="8000,..." run the preset and
# ideal robots of those seeds (effects "unseen_preset", "unseen_ideal").
# SLIP_EFFECTS="randomized unseen" limits slip1, slip3 and bigslip to those
# populations (default all).
#   bash scripts/study_monitor_population.sh [DIR] [COUNT]
#   (default out/monitor_population, 10 robots a population; ~1.5 minutes a population of 10 on 2 idle cores)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/monitor_population}
count=${2:-10}
gpm=${GPM:-./build/app/gpm}
[[ -x $gpm ]] || bash scripts/build.sh
mkdir -p "$out"
scenario=scenarios/monitor_population.yaml
# The scenario's variants (robot path made absolute: they live in DIR).
robot=$(realpath models/gpm2002.yaml)
variant_file() {  # variant -> its scenario in DIR, checked to say what it should
  local v=$1 f=$out/monitor_population_$1.yaml
  local e=(-e "s|^robot: .*|robot: $robot|") want
  case $v in
    learning) want="^monitor: data_sheet" ;;
    nolearning) e+=(-e "s|^monitor: data_sheet.*|monitor: {preset: data_sheet, learning_s: 0}|"); want="learning_s: 0" ;;
    nomap) e+=(-e "s|^monitor: data_sheet.*|monitor: {preset: data_sheet, map_radius_rad: 0}|"); want="map_radius_rad: 0" ;;
    slip1) e+=(-e "s|dth2: 1.0e-4|dth1: 1.0e-4|"); want="dth1: 1.0e-4" ;;
    slip3) e+=(-e "s|dth2: 1.0e-4|dth3: 1.0e-4|"); want="dth3: 1.0e-4" ;;
    bigslip) e+=(-e "s|dth2: 1.0e-4|dth2: 1.0e-3|"); want="dth2: 1.0e-3" ;;
    *) echo "study_monitor_population.sh: unknown variant '$v' (nolearning, nomap, learning, slip1, slip3, bigslip)" >&2; exit 2 ;;
  esac
  sed "${e[@]}" "$scenario" > "$f"
  grep -q "$want" "$f"
  echo "$f"
}
effects_list=(randomized); [[ ${PRESET:-0} == 1 ]] && effects_list+=(preset); [[ -n ${UNSEEN:-} ]] && effects_list+=(unseen)
[[ ${IDEAL:-0} == 1 ]] && effects_list+=(ideal)
[[ -n ${UNSEEN_PRESET:-} ]] && effects_list+=(unseen_preset); [[ -n ${UNSEEN_IDEAL:-} ]] && effects_list+=(unseen_ideal)
[[ ${TABLE_ONLY:-0} == 1 ]] && RUN_EFFECTS=" "  # TABLE_ONLY=1: tabulate what DIR holds
for effects in ${RUN_EFFECTS:-${effects_list[@]}}; do
  flag=(--count "$count"); [[ $effects == preset ]] && flag+=(--keep-effects)
  [[ $effects == unseen ]] && flag=(--seeds "$UNSEEN")
  [[ $effects == unseen_preset ]] && flag=(--seeds "$UNSEEN_PRESET" --keep-effects)
  for variant in ${VARIANTS:-nolearning nomap learning}; do
    [[ $variant =~ slip && -n ${SLIP_EFFECTS:-} && " $SLIP_EFFECTS " != *" $effects "* ]] && continue
    s=$(variant_file "$variant")
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
label = {"nolearning": "without learning", "nomap": "learning phase without the map",
         "learning": "learning phase and configuration map (the default)",
         "slip1": "the default, slip of encoder 1", "slip3": "the default, slip of encoder 3",
         "bigslip": "the default, slip 1e-3 rad"}
for effects in effects_list:
    pops = {}
    for variant in label:
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
    if "learning" in pops:
        by_variant = {v: {r["seed"]: r for r in pops[v]["robots"]} for v in ("nolearning", "nomap", "slip1", "slip3", "bigslip")
                      if v in pops}
        def cells(x):
            mon = x.get("monitor")
            if not mon:
                return ["failed" if x.get("failure") else "-", "-", "-"]
            d = mon["detection_delay_s"]
            named = re.search(r"\((\w+) ", mon["detection"] or "")
            return [f"{mon['false_alarms']} ({num(mon['false_alarms_per_hour'], '.0f')}/h)",
                    "missed" if d is None else f"{d:.3f} s ({named.group(1) if named else '?'})",
                    num(mon.get("learned_scale"), ".2f")]
        for r in pops["learning"]["robots"]:
            cb = cells(by_variant.get("nolearning", {}).get(r["seed"], {}))
            cn = cells(by_variant.get("nomap", {}).get(r["seed"], {}))
            cd = cells(r)
            cs = [cells(by_variant.get(v, {}).get(r["seed"], {})) for v in ("slip1", "slip3", "bigslip")]
            per_robot.append(f"| {effects} | {r['seed']} | {cb[0]} | {cb[1]} | {cn[0]} | {cn[1]} | {cn[2]} | "
                             f"{cd[0]} | {cd[1]} | {cd[2]} | " + " | ".join(f"{c[0]}, {c[1]}" if c[1] != "-" else c[0] for c in cs) + " |")
md = ["| effects | monitor | robots | false alarms (healthy time after learning) | per hour | robots with any | "
      "slip detected | delay median / worst (s) |",
      "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"] + summary + ["",
      "Per robot (false alarms in the healthy time, per hour; detection delay of the slip of encoder 2 and the "
      "parameter it was named as; the innovation scale learnt, 1 = as stated; the default monitor's false alarms and "
      "delay with the slip of encoder 1, of encoder 3, and of 1e-3 rad on encoder 2; - when not run):", "",
      "| effects | seed | without learning: false alarms | without learning: slip | learning without map: false alarms | "
      "learning without map: slip | learnt scale | default: false alarms | default: slip | default: learnt scale | "
      "default, slip of encoder 1 | default, slip of encoder 3 | default, slip 1e-3 rad |",
      "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"] + per_robot
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
