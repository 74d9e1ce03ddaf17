#!/usr/bin/env bash
# Screenshot of the main job's report for the README (docs/img/report.png;
# scripts/readme_pictures.sh runs it and records the figures it shows):
# headless Chromium renders out/main/report.html (made by scripts/run.sh when
# missing) in a 1000 px window, cropped to its first HEIGHT px (default 1500:
# the accuracy and parameter tables). The PNG is written beside the target and
# renamed into place; Chromium's profile lives in a temporary folder that is
# removed on exit.
#   bash scripts/screenshot_report.sh [REPORT.html] [OUT.png] [HEIGHT]
set -euo pipefail
cd "$(dirname "$0")/.."
report=${1:-out/main/report.html}
out=${2:-docs/img/report.png}
height=${3:-1500}
max_bytes=300000

command -v chromium >/dev/null || { echo "screenshot_report: chromium is not installed (bash scripts/setup.sh installs it)" >&2; exit 2; }
if [[ ! -f $report ]]; then
  if [[ $report == out/main/report.html ]]; then
    bash scripts/run.sh out/main
  else
    echo "screenshot_report: $report: no such file (give the report.html of a gpm run)" >&2
    exit 2
  fi
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out.tmp.$$"' EXIT
mkdir -p "$(dirname "$out")"
HOME=$tmp XDG_CONFIG_HOME=$tmp/config XDG_CACHE_HOME=$tmp/cache timeout 120 chromium \
  --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars \
  --user-data-dir="$tmp/profile" --window-size="1000,$height" --force-device-scale-factor=1 \
  --screenshot="$tmp/report.png" "file://$(realpath "$report")" 2>"$tmp/stderr.txt" >/dev/null ||
  { echo "screenshot_report: chromium failed:" >&2; cat "$tmp/stderr.txt" >&2; exit 1; }
[[ -s $tmp/report.png ]] || { echo "screenshot_report: chromium wrote no screenshot" >&2; exit 1; }
bytes=$(stat -c %s "$tmp/report.png")
if ((bytes > max_bytes)); then
  echo "screenshot_report: $bytes bytes, more than $max_bytes: give a smaller HEIGHT" >&2
  exit 1
fi
mv "$tmp/report.png" "$out.tmp.$$" && mv "$out.tmp.$$" "$out"
echo "screenshot_report: $out ($bytes bytes) from $report"
