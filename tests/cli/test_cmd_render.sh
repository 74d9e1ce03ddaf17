#!/usr/bin/env bash
# Tests of app/cmd_render.cpp: gpm render writes an H.264 MP4 that ffprobe
# reads with the requested size and frame count and a PNG frame; the same
# scenario gives identical files; bad camera, size or output path exits 2
# with one line and leaves nothing behind; MuJoCo never writes MUJOCO_LOG.TXT.
set -u
GPM="$1"
source "$(dirname "$0")/cli_lib.sh"
unset DISPLAY

cat >"$tmp/s.yaml" <<'YAML'
name: render_cli
seed: 4
path: {shape: circle, centre: [216.5, 250], radius: 15, period_s: 0.4}
render: {size: 160x120, fps: 20}
YAML
cd "$tmp" || exit 1

check "render" 0 "$GPM" render s.yaml -o a.mp4 --frame-png 3:a.png </dev/null
expect_out "summary" "^frames +[0-9]+ at 20 fps, 160x120, camera top, quality fast"
n=$(sed -nE 's/^frames +([0-9]+) at.*/\1/p' "$tmp/out")
probe=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=codec_name,width,height,nb_read_frames -of csv=p=0 a.mp4)
if [[ "$probe" == "h264,160,120,$n" ]]; then passed=$((passed+1)); else echo "FAIL ffprobe: '$probe', want h264,160,120,$n"; fail=$((fail+1)); fi
if [[ -s a.png ]]; then passed=$((passed+1)); else echo "FAIL no PNG"; fail=$((fail+1)); fi
check "render again, options override the section" 0 "$GPM" render s.yaml -o b.mp4 --frame-png 3:b.png --size 160x120 --fps 20 --camera top
if cmp -s a.mp4 b.mp4 && cmp -s a.png b.png; then passed=$((passed+1)); else echo "FAIL same scenario, different files"; fail=$((fail+1)); fi

check "unknown camera" 2 "$GPM" render s.yaml -o c.mp4 --camera front
expect_err "camera names" "--camera: unknown camera 'front' \(valid: top, oblique\)"
check "size too big" 2 "$GPM" render s.yaml -o c.mp4 --size 8000x480
expect_err "maximum" "maximum 4096x4096"
check "size not positive" 2 "$GPM" render s.yaml -o c.mp4 --size 0x480
check "unwritable output" 2 "$GPM" render s.yaml -o /nonexistent-gpm-folder/c.mp4
check "frame beyond the video" 2 "$GPM" render s.yaml -o c.mp4 --frame-png 100000:c.png
if [[ ! -e c.mp4 && ! -e c.png && -z "$(ls -A | grep '^\.')" ]]; then passed=$((passed+1)); else echo "FAIL partial files:"; ls -la; fail=$((fail+1)); fi
if [[ ! -e MUJOCO_LOG.TXT ]]; then passed=$((passed+1)); else echo "FAIL MUJOCO_LOG.TXT written"; fail=$((fail+1)); fi
finish
