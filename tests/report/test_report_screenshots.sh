#!/usr/bin/env bash
# Tests of report/run_report.cpp and report/report_document.cpp as a reader
# sees them: `gpm run` writes the report of a short scenario
# (tests/fixtures/report_small.yaml), headless Chromium shows report.html
# in a 1280x800 window and a 390x844 phone, and a script in the page fails
# the test when the page scrolls sideways (scrollWidth > innerWidth),
# Markdown or machine formatting shows as text, or the first screen lacks
# the before/after sentence; every table of report.md has its header's cell
# count; a screenshot of each window must be a PNG of
# that size with something drawn. The report of `gpm monitor
# scenarios/monitor_offset_jump.yaml` (report/monitor_report.cpp, 60 s of
# operation in about 2 s) likewise on the phone, its lead the alarms.
# GPM_SCREENSHOTS=DIR keeps the PNGs there (to look at them). Skipped (exit 0, a note) when chromium is not
# installed (scripts/setup.sh installs it).
#   test_report_screenshots.sh GPM SOURCE_DIR
set -u
GPM="$1"; SRC="$2"
source "$SRC/tests/cli/cli_lib.sh"
chromium=$(command -v chromium || true)
if [[ -z $chromium ]]; then echo "SKIP: chromium is not installed (scripts/setup.sh installs it)"; exit 0; fi

check "gpm run report_small" 0 "$GPM" run "$SRC/tests/fixtures/report_small.yaml" -o "$tmp/run" --quiet
check "gpm monitor monitor_offset_jump" 0 "$GPM" monitor "$SRC/scenarios/monitor_offset_jump.yaml" -o "$tmp/monitor"

# Every GFM table of both report.md files: each row has its header's cell count
# (cells split at pipes not escaped by a backslash; tests/report/report_text_checks.hpp).
for report in run monitor; do
  python3 - "$tmp/$report/report.md" >"$tmp/tables.txt" <<'PY'
import re, sys
lines = open(sys.argv[1], encoding="utf-8").read().split("\n")
def cells(line):
    c = re.split(r"(?<!\\)\|", line)
    return len(c) - (line.strip().startswith("|")) - (line.strip().endswith("|"))
tables = 0
for i in range(len(lines) - 1):
    if "|" in lines[i] and re.match(r"^\s*\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)*\|?\s*$", lines[i + 1]):
        tables += 1
        j = i + 1
        while j < len(lines) and "|" in lines[j]:
            if cells(lines[j]) != cells(lines[i]):
                print(f"row of {cells(lines[j])} cells under {cells(lines[i])}: {lines[j]}")
            j += 1
print(f"tables {tables}")
PY
  holds "$report report.md: every table row has its header's cell count" grep -qx "tables [1-9][0-9]*" "$tmp/tables.txt"
  [[ $(wc -l <"$tmp/tables.txt") -eq 1 ]] && passed=$((passed+1)) || { echo "FAIL $report report.md:"; cat "$tmp/tables.txt"; fail=$((fail+1)); }
done

# The page's verdict, written into the DOM that --dump-dom prints.
cat >"$tmp/check.js" <<'JS'
(function () {
  const bad = [];
  const root = document.documentElement;
  if (root.scrollWidth > window.innerWidth)
    bad.push(`page scrolls sideways: ${root.scrollWidth} px wide in a ${window.innerWidth} px window`);
  // The text a reader sees: figures, code and preformatted text left out.
  let text = '';
  const walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT, {
    acceptNode: (n) => n.parentElement.closest('svg, code, pre, script, style') ? NodeFilter.FILTER_REJECT
                                                                                : NodeFilter.FILTER_ACCEPT });
  for (let n = walk.nextNode(); n; n = walk.nextNode()) text += n.textContent + '\n';
  const leaks = {backtick: /`/, emphasis: /\*\*/, 'link or image': /\]\(|!\[/, 'escaped pipe': /\\\|/,
                 'table rule': /\|\s*---/, 'C exponent': /[0-9]\.?[0-9]*e[+-][0-9]+/,
                 'ASCII unit': /[0-9] ?u(m|rad|s)\b/};
  for (const [name, re] of Object.entries(leaks)) {
    const m = text.match(re);
    if (m) bad.push(`leaked ${name}: ...${text.slice(Math.max(0, m.index - 40), m.index + 40).replace(/\n/g, ' ')}...`);
  }
  const lead = document.querySelector('p.lead');
  if (!lead) bad.push('no lead sentence');
  else {
    const r = lead.getBoundingClientRect();
    if (r.bottom > window.innerHeight) bad.push(`lead sentence below the first screen (${r.bottom} > ${window.innerHeight} px)`);
    if (!window.LEAD.test(lead.textContent)) bad.push(`the lead does not match ${window.LEAD}: ${lead.textContent}`);
  }
  const out = document.createElement('pre');
  out.id = 'verdict';
  out.textContent = bad.length ? bad.join('\n') : 'OK';
  document.body.appendChild(out);
  parent.postMessage(out.textContent, '*');  // to the frame's page, which --dump-dom prints
})();
JS
# A headless window is at least 500 px wide and its height includes the
# window's frame, so the report is checked in a frame of the exact size
# (its innerWidth and innerHeight), inside a page that shows the frame's verdict.
frame_page() {  # WIDTH HEIGHT
  echo "<html><body style=\"margin:0\"><pre id=\"verdict\"></pre><script>addEventListener('message', (e) => {
    document.getElementById('verdict').textContent = e.data; });</script><iframe src=\"checked.html\" width=\"$1\"
    height=\"$2\" style=\"border:0;display:block\"></iframe></body></html>"
}

# Runs chromium on page.html in a WxH window with an action; HOME and the
# profile live in $tmp, nothing is written elsewhere.
browse() {
  HOME="$tmp" XDG_CONFIG_HOME="$tmp/config" XDG_CACHE_HOME="$tmp/cache" timeout 120 "$chromium" \
    --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars --user-data-dir="$tmp/profile" \
    --window-size="$1" --force-device-scale-factor=1 "${@:2}" "file://$tmp/page.html" 2>>"$tmp/chromium.txt"
}

# PNG width and height (IHDR, big-endian at bytes 16 and 20).
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}'; }

# The lead each report must show on its first screen.
run_lead='/nominal model.*[0-9.]+\s(mm|µm)\s.*calibrated.*[0-9.]+\s(mm|µm) away/'
monitor_lead='/[0-9.]+ s of normal operation the drift monitor raised [0-9]+ alarm.*detected/'
for job in run,1280,800 run,390,844 monitor,390,844; do
  IFS=, read -r report w h <<<"$job"; size=$w,$h
  lead_var=${report}_lead
  { sed '$ s|</body></html>$||' "$tmp/$report/report.html"; echo "<script>window.LEAD = ${!lead_var};</script><script>"
    cat "$tmp/check.js"; echo '</script></body></html>'; } >"$tmp/checked.html"
  frame_page "$w" "$h" >"$tmp/page.html"
  verdict=$(browse 1320,900 --virtual-time-budget=5000 --dump-dom | sed -z 's/.*<pre id="verdict">//; s/<\/pre>.*//' |
    sed 's/&lt;/</g; s/&gt;/>/g; s/&quot;/"/g; s/&amp;/\&/g')
  if [[ $verdict == OK ]]; then passed=$((passed+1)); else echo "FAIL $report report at $size: ${verdict:-no verdict; chromium said: $(cat "$tmp/chromium.txt")}"; fail=$((fail+1)); fi
  cp "$tmp/$report/report.html" "$tmp/page.html"
  rm -f "$tmp/shot.png"
  browse "$size" --screenshot="$tmp/shot.png" >/dev/null
  want=${size/,/x}
  holds "$report screenshot at $size is a ${want} PNG" test "$(png_size "$tmp/shot.png" 2>/dev/null)" = "$want"
  # A first screen of text and tables compresses to well over 10 kB; a blank page to a few hundred bytes.
  holds "$report screenshot at $size is not blank" test "$(stat -c %s "$tmp/shot.png" 2>/dev/null || echo 0)" -gt 10000
  if [[ -n ${GPM_SCREENSHOTS:-} ]]; then mkdir -p "$GPM_SCREENSHOTS" && cp "$tmp/shot.png" "$GPM_SCREENSHOTS/${report}_${want}.png"; fi
done
finish
