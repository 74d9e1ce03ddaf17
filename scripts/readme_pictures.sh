#!/usr/bin/env bash
# Makes the README's pictures from one run and records what they show, so a
# test can tell when a picture no longer shows what the code gives:
#   docs/img/report.png   the top of the report of `gpm run scenarios/main.yaml`
#                         (scripts/screenshot_report.sh, 1000 px wide)
#   docs/img/report.json  its source: the scenario's and robot file's sha256, the
#                         picture's sha256, the report's lead sentence and the
#                         figures it shows, read from the run's summary.json
#   docs/img/frame.png    with --frame: a frame of `gpm render scenarios/main.yaml`
#   docs/img/frame.json   (scripts/readme_frame.sh) and its sources' sha256
# tests/report/test_readme_pictures.sh checks them (and, labelled long, runs
# the scenario again and compares the figures).
#   bash scripts/readme_pictures.sh [BUILD_DIR] [--frame]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
frame=0
for a in "$@"; do
  case $a in
    --frame) frame=1 ;;
    *) build=$(realpath "$a") ;;
  esac
done
gpm=$build/app/gpm
[[ -x $gpm ]] || { echo "readme_pictures: $gpm: not built (bash scripts/build.sh builds it)" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# From the root, so the report names the scenario as a reader of the README finds it.
(cd "$root" && "$gpm" run scenarios/main.yaml -o "$tmp/main" --quiet) || {
  echo "readme_pictures: gpm run scenarios/main.yaml failed; the pictures are left as they were" >&2; exit 1; }
bash "$root/scripts/screenshot_report.sh" "$tmp/main/report.html" "$root/docs/img/report.png" 1500
python3 "$root/scripts/readme_figures.py" "$root" "$tmp/main" >"$root/docs/img/report.json.tmp"
mv "$root/docs/img/report.json.tmp" "$root/docs/img/report.json"
echo "readme_pictures: docs/img/report.png and docs/img/report.json from scenarios/main.yaml"

if ((frame)); then
  bash "$root/scripts/readme_frame.sh" "$build"
  python3 "$root/scripts/readme_figures.py" --frame "$root" >"$root/docs/img/frame.json.tmp"
  mv "$root/docs/img/frame.json.tmp" "$root/docs/img/frame.json"
  echo "readme_pictures: docs/img/frame.png and docs/img/frame.json"
fi
