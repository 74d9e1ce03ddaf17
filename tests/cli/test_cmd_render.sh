#!/usr/bin/env bash
# Tests of app/cmd_render.cpp: gpm render writes an H.264 MP4 that ffprobe
# reads with the requested size and frame count and a PNG frame; the same
# scenario gives identical files; bad camera, size, output path or suffix
# exits 2 with one line and leaves nothing behind; a gpm run scenario is
# shown as its story (nominal, sampling, calibrated, in that order); off a
# terminal nothing but the summary is printed; MuJoCo never writes
# MUJOCO_LOG.TXT.
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
check "fps 0" 2 "$GPM" render s.yaml -o c.mp4 --fps 0
expect_err "fps message" "--fps: must be in \(0, 240\], got 0"
check "speed 0" 2 "$GPM" render s.yaml -o c.mp4 --speed 0
expect_err "speed message" "--speed: must be positive, got 0"

# The suffix names the format: anything but .mp4 for -o and .png for
# --frame-png is refused before anything is simulated (issue 19: -o video.avi
# used to write MP4 silently).
check "avi refused" 2 "$GPM" render s.yaml -o c.avi
expect_err "suffix message" "^gpm: error: -o c.avi: gpm render writes H.264 MP4 only: give a name ending in .mp4 \(got '.avi'\)$"
check "no suffix refused" 2 "$GPM" render s.yaml -o video
expect_err "no suffix message" "give a name ending in .mp4 \(got no suffix\)"
check "jpg frame refused" 2 "$GPM" render s.yaml --frame-png 1:c.jpg
expect_err "png suffix message" "--frame-png c.jpg: gpm render writes PNG only"
check "upper-case suffix accepted" 0 "$GPM" render s.yaml -o C.MP4
if [[ ! -e c.avi && ! -e video && ! -e c.jpg ]]; then passed=$((passed+1)); else echo "FAIL refused outputs written"; fail=$((fail+1)); fi
rm -f C.MP4
# Off a terminal (here stderr is a file) no progress line is written.
if [[ ! -s "$tmp/err" ]]; then passed=$((passed+1)); else echo "FAIL stderr not empty off a terminal:"; cat "$tmp/err"; fail=$((fail+1)); fi

# A gpm run scenario is shown as a story: an opening card (5 s: 100 frames at
# 20 fps, per page when it takes more than one at this size), the nominal
# controller on the test path (a 0.4 s circle: 9 frames), the sampling, the
# calibrated controller on the same path (9 frames) and a closing card (100
# frames a page), in that order. Under 320x240 a story is refused (one line
# naming the flag and the valid sizes).
cat >run.yaml <<'YAML'
name: render_story
seed: 3
actual: {geometry: {dth1: 0.01, dth2: -0.01, dth3: 0.01}}
encoder: {bits: 0, noise_rad: 0}
sampling: {pattern: disc, centre: [216.5, 250], radius: 60, count: 3, move_speed_mm_s: 400}
calibration: {cost: j2, method: lm, fix: [xa1, ya1, xa2, ya2, xa3, ya3, la1, la2, la3, lb1, lb2, lb3]}
compensation: {count: 2, radius: 20, path: {shape: circle, centre: [216.5, 250], radius: 15, period_s: 0.4}}
render: {size: 320x240, fps: 20}
YAML
check "story too small" 2 "$GPM" render run.yaml -o story.mp4 --size 160x120
expect_err "story size message" "^gpm: error: --size: size 160x120 is too small for the story's cards \(valid: 320x240 to 4096x4096, even; --simulation-only"
check "story" 0 "$GPM" render run.yaml -o story.mp4
parts=$(sed -nE 's/^(part|card) +([0-9]\/3 )?([a-z]+) .*from frame ([0-9]+)$/\2\3 \4/p' "$tmp/out" | tr '\n' ';')
total=$(sed -nE 's/^frames +([0-9]+) at.*/\1/p' "$tmp/out")
pages_of() { local p; p=$(sed -nE "s/^card +$1 in ([0-9]+) pages .*/\1/p" "$tmp/out"); echo "${p:-1}"; }
open=$((100 * $(pages_of opening))); close=$((100 * $(pages_of closing)))
if [[ "$parts" == "opening 0;1/3 nominal $open;2/3 sampling $((open + 9));3/3 calibrated $((total - close - 9));closing $((total - close));" ]]; then passed=$((passed+1))
else echo "FAIL story parts: '$parts' (total $total)"; cat "$tmp/out"; fail=$((fail+1)); fi
cp "$tmp/out" story_out.txt
# The closing card's figures are what gpm run measures for this scenario
# (summary.json), 3 significant digits, um below 1 mm.
check "gpm run of the story" 0 "$GPM" run run.yaml -o run_dir --quiet
python3 - run_dir/summary.json story_out.txt >card_check.txt <<'PY'
import json, math, sys
acc = json.load(open(sys.argv[1]))["accuracy"]
def sig(v):
    whole = math.floor(math.log10(abs(v))) + 1 if v else 1
    return f"{v:.{max(0, 3 - whole)}f}"
def distance(um):
    return sig(um) + " um" if float(sig(um)) < 1000 else sig(um / 1000) + " mm"
want = [f"error RMS        at 2 poses: {distance(acc['nominal']['static_rms_um'])} nominal, "
        f"{distance(acc['calibrated']['static_rms_um'])} calibrated",
        f"error RMS        on the path: {distance(acc['nominal']['path_rms_um'])} nominal, "
        f"{distance(acc['calibrated']['path_rms_um'])} calibrated"]
got = [l.rstrip("\n") for l in open(sys.argv[2]) if l.startswith("error RMS")]
print("ok" if got == want else f"closing card {got}, gpm run {want}")
PY
if [[ "$(cat card_check.txt)" == ok ]]; then passed=$((passed+1)); else echo "FAIL $(cat card_check.txt)"; fail=$((fail+1)); fi
rm -rf run_dir story_out.txt card_check.txt
probe=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 story.mp4)
if [[ "$probe" == "$total" ]]; then passed=$((passed+1)); else echo "FAIL story frames: ffprobe $probe, summary $total"; fail=$((fail+1)); fi
# --simulation-only: the sampling alone, as many frames as the story's second part.
check "simulation only" 0 "$GPM" render run.yaml -o sim.mp4 --simulation-only
n=$(sed -nE 's/^frames +([0-9]+) at.*/\1/p' "$tmp/out")
if [[ "$n" -eq $((total - open - close - 18)) ]] && ! grep -qE '^(part|card)' "$tmp/out"; then passed=$((passed+1)); else echo "FAIL simulation only: $n frames, want $((total - open - close - 18))"; fail=$((fail+1)); fi
rm -f story.mp4 sim.mp4 run.yaml

# Output policy (models/output_file.hpp): the scenario is never overwritten, a
# device is written in place, a symlink is followed.
cp s.yaml s_before.yaml
check "output is the scenario" 2 "$GPM" render s.yaml -o s.yaml
expect_err "input message" "s.yaml: is also an input of this command"
if cmp -s s.yaml s_before.yaml; then passed=$((passed+1)); else echo "FAIL scenario overwritten"; fail=$((fail+1)); fi
rm -f s_before.yaml
check "frame to /dev/null" 0 "$GPM" render s.yaml --frame-png 1:/dev/null
if [[ -c /dev/null ]]; then passed=$((passed+1)); else echo "FAIL /dev/null is no longer a device"; fail=$((fail+1)); fi
mkdir -p sub && ln -s sub/real.png link.png
check "frame through a symlink" 0 "$GPM" render s.yaml --frame-png 1:link.png
if [[ -L link.png && -s sub/real.png ]]; then passed=$((passed+1)); else echo "FAIL symlink not followed"; fail=$((fail+1)); fi
rm -rf sub link.png

# Interrupted (SIGINT) while encoding: exit 130, no video and no temporary.
cat >long.yaml <<'YAML'
name: render_cli_long
seed: 4
path: {shape: circle, centre: [216.5, 250], radius: 15, period_s: 0.4, revolutions: 100}
render: {size: 160x120, fps: 20}
YAML
# Frame 5 goes to a FIFO (written in place): once it has been read whole,
# the video is being encoded (its temporary made before the first frame).
# The script waits on that, not on the wall clock (timeout only bounds a
# render that failed before frame 5).
mkfifo frame5.fifo
"$GPM" render long.yaml -o long.mp4 --frame-png 5:frame5.fifo >/dev/null 2>"$tmp/int.err" &
pid=$!
timeout 300 cat frame5.fifo >/dev/null
if compgen -G '.long.mp4.tmp*' >/dev/null; then passed=$((passed+1)); else echo "FAIL no temporary while encoding"; fail=$((fail+1)); fi
kill -INT "$pid" 2>/dev/null
wait "$pid"; got=$?
if [[ $got -eq 130 ]]; then passed=$((passed+1)); else echo "FAIL interrupted render: exit $got, want 130"; cat "$tmp/int.err"; fail=$((fail+1)); fi
if [[ ! -e long.mp4 && -z "$(ls -A | grep '^\.')" ]]; then passed=$((passed+1)); else echo "FAIL interrupted render left:"; ls -la; fail=$((fail+1)); fi
rm -f long.yaml frame5.fifo

# The renderer is a separate executable: gpm links neither OSMesa nor libav,
# and without gpm-render next to it, gpm render says so in one line (exit 2).
if ldd "$GPM" | grep -qE 'OSMesa|avcodec'; then echo "FAIL gpm links the renderer"; fail=$((fail+1)); else passed=$((passed+1)); fi
mkdir alone && cp "$GPM" alone/gpm
check "renderer missing" 2 ./alone/gpm render s.yaml -o c.mp4
expect_err "renderer message" "cannot run the renderer .*/alone/gpm-render"
rm -rf alone

if [[ ! -e MUJOCO_LOG.TXT ]]; then passed=$((passed+1)); else echo "FAIL MUJOCO_LOG.TXT written"; fail=$((fail+1)); fi
finish
