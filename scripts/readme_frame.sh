#!/usr/bin/env bash
# Makes docs/img/frame.png, the frame of the README: renders the story of
# scenarios/main.yaml (gpm render: nominal controller, sampling, calibrated
# controller) and extracts, with ffmpeg, the frame FRAME of the video (by
# default two thirds into the sampling part), checking it stays under 300 kB.
#   bash scripts/readme_frame.sh [BUILD_DIR] [FRAME]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$build/app/gpm" render "$root/scenarios/main.yaml" -o "$tmp/story.mp4" | tee "$tmp/summary.txt"
if [[ $# -ge 2 ]]; then
  frame=$2
else
  # Parts: "part  2/3 sampling for the calibration from frame N".
  first=$(sed -nE 's/^part +2\/3 .* from frame ([0-9]+)$/\1/p' "$tmp/summary.txt")
  next=$(sed -nE 's/^part +3\/3 .* from frame ([0-9]+)$/\1/p' "$tmp/summary.txt")
  frame=$(( first + 2 * (next - first) / 3 ))
fi
mkdir -p "$root/docs/img"
ffmpeg -v error -y -i "$tmp/story.mp4" -vf "select=eq(n\,$frame)" -frames:v 1 "$tmp/frame.png"
size=$(stat -c %s "$tmp/frame.png")
if (( size >= 300000 )); then echo "readme_frame: frame $frame is $size bytes (limit 300 kB)" >&2; exit 1; fi
mv "$tmp/frame.png" "$root/docs/img/frame.png"
echo "wrote docs/img/frame.png (frame $frame, $size bytes)"
