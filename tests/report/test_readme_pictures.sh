#!/usr/bin/env bash
# Tests of scripts/readme_pictures.sh's output, the README's pictures:
# docs/img/report.png is the picture docs/img/report.json describes (its
# sha256), made from today's scenarios/main.yaml and robot file (their
# sha256: a changed scenario makes the picture stale), and the lead sentence
# it shows states the figures recorded; frame.png likewise when frame.json
# is there. With GPM (labelled long), `gpm run scenarios/main.yaml` runs again
# and must give the recorded figures (3 significant digits, as the report
# shows them): a picture older than what the code gives fails here.
#   test_readme_pictures.sh SOURCE_DIR [GPM]
set -u
SRC="$1"; GPM="${2:-}"
source "$SRC/tests/cli/cli_lib.sh"
img="$SRC/docs/img"

sha() { sha256sum "$1" | cut -d' ' -f1; }
field() { python3 -c 'import json,sys; v=json.load(open(sys.argv[1])); [v:=v[k] for k in sys.argv[2:]]; print(v)' "$@"; }

holds "report.json exists (bash scripts/readme_pictures.sh writes it)" test -f "$img/report.json"
holds "report.png is the picture report.json describes" \
  test "$(sha "$img/report.png")" = "$(field "$img/report.json" picture_sha256)"
holds "report.png made from today's scenarios/main.yaml (else: bash scripts/readme_pictures.sh)" \
  test "$(sha "$SRC/scenarios/main.yaml")" = "$(field "$img/report.json" source_sha256)"
holds "report.png made with today's models/gpm2002.yaml" \
  test "$(sha "$SRC/models/gpm2002.yaml")" = "$(field "$img/report.json" robot_sha256)"
# The lead sentence the picture shows states the recorded before and after
# (3 significant digits, mm from 1000 um on, as the report writes them).
python3 - "$img/report.json" >"$tmp/lead.txt" <<'PY'
import json, math, sys
f = json.load(open(sys.argv[1]))["figures"]
def sig(v):
    whole = math.floor(math.log10(abs(v))) + 1
    return f"{v:.{max(0, 3 - whole)}f}"
def distance(um):
    return sig(um / 1000) + " mm" if abs(um) >= 1000 else sig(um) + " µm"
lead = (f["lead"] or "").replace("\u00a0", " ")  # a number and its unit joined by a no-break space
for want in (f"stood {distance(f['nominal_static_rms_um'])} from", f"it stands {distance(f['calibrated_static_rms_um'])} away"):
    print("ok" if want in lead else f"the lead '{lead}' does not say '{want}'")
PY
while read -r line; do holds "report.json's lead: $line" test "$line" = ok; done <"$tmp/lead.txt"

if [[ -f $img/frame.json ]]; then
  holds "frame.png is the picture frame.json describes" \
    test "$(sha "$img/frame.png")" = "$(field "$img/frame.json" picture_sha256)"
  holds "frame.png made from today's scenarios/main.yaml" \
    test "$(sha "$SRC/scenarios/main.yaml")" = "$(field "$img/frame.json" source_sha256)"
fi

if [[ -n $GPM ]]; then
  check "gpm run scenarios/main.yaml" 0 "$GPM" run "$SRC/scenarios/main.yaml" -o "$tmp/main" --quiet
  python3 "$SRC/scripts/readme_figures.py" --figures "$tmp/main" >"$tmp/now.json"
  python3 -c 'import json,sys; print(json.dumps(json.load(open(sys.argv[1]))["figures"], indent=2, ensure_ascii=False))' \
    "$img/report.json" >"$tmp/recorded.json"
  if diff "$tmp/recorded.json" "$tmp/now.json" >"$tmp/diff.txt"; then
    passed=$((passed+1))
  else
    echo "FAIL the README's report.png shows other figures than gpm run gives today (bash scripts/readme_pictures.sh):"
    cat "$tmp/diff.txt"; fail=$((fail+1))
  fi
fi
finish
