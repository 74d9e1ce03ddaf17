// Tests of report/report_document.cpp's HTML (and report/run_report.cpp's
// figures) in a real browser: headless Chromium loads the page, a small
// script measures every element (nothing wider than its box, nothing past
// the page's edge, every figure drawn with a size and nothing of it clipped)
// and writes its verdict into the DOM, which --dump-dom prints. Skipped only
// when chromium is not installed (scripts/setup.sh installs it).
#include "report/report_document.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "report/monitor_report.hpp"
#include "report/paper_report.hpp"
#include "report/run_report.hpp"
#include "run_report_fixture.hpp"

namespace gpm::report {
namespace {

namespace fs = std::filesystem;

// The measuring script: appended to the page, run after layout.
constexpr const char* kCheckScript = R"JS(
(function () {
  const bad = [];
  const root = document.documentElement;
  if (root.scrollWidth > window.innerWidth)
    bad.push(`page: ${root.scrollWidth} px wide in a ${window.innerWidth} px window`);
  const name = (e) => `<${e.tagName.toLowerCase()}> "${(e.textContent || '').trim().slice(0, 40)}"`;
  const body = document.body.getBoundingClientRect();
  // A box that scrolls (a wide table's div.scroll) may hold more than it shows.
  const scrolls = (e) => ['auto', 'scroll'].includes(getComputedStyle(e).overflowX);
  const inScroller = (e) => { for (let p = e.parentElement; p; p = p.parentElement) if (scrolls(p)) return true; return false; };
  for (const e of document.body.querySelectorAll('*')) {
    if (e instanceof SVGElement && !(e instanceof SVGSVGElement && e.parentElement instanceof HTMLElement)) continue;
    if (inScroller(e)) continue;
    if (!(e instanceof SVGElement) && !scrolls(e) && e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1)
      bad.push(`overflows its box: ${name(e)} ${e.scrollWidth} > ${e.clientWidth} px`);
    const r = e.getBoundingClientRect();
    const parent = e.parentElement.getBoundingClientRect();
    const outside = (q) => q.width > 0 && (q.right > body.right + 1 || q.left < body.left - 1);
    if (outside(r) && !outside(parent)) bad.push(`sticks out of the page: ${name(e)}`);
  }
  const figures = document.querySelectorAll('figure');
  for (const f of figures) {
    const img = f.querySelector(':scope > svg, :scope > img');
    if (!img) { bad.push(`figure ${f.id}: no image`); continue; }
    const r = img.getBoundingClientRect();
    if (r.width < 1 || r.height < 1) { bad.push(`figure ${f.id}: drawn with no size`); continue; }
    for (const c of img.querySelectorAll('text, circle, rect, path, line, polygon, polyline')) {
      const q = c.getBoundingClientRect();
      if (q.width === 0 && q.height === 0) continue;
      if (q.left < r.left - 0.5 || q.right > r.right + 0.5 || q.top < r.top - 0.5 || q.bottom > r.bottom + 0.5)
        bad.push(`figure ${f.id}: clipped ${name(c)}`);
    }
  }
  for (const i of document.images) if (!i.complete || i.naturalWidth === 0) bad.push(`broken image ${i.src}`);
  const out = document.createElement('pre');
  out.id = 'verdict';
  out.textContent = `figures ${figures.length}\n` + (bad.length ? bad.join('\n') : 'OK');
  document.body.appendChild(out);
  parent.postMessage(out.textContent, '*');  // to the frame's page (verdict())
})();
)JS";

// The chromium executable on PATH, or empty.
std::string find_chromium() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path p = fs::path(dir) / "chromium";
    if (!dir.empty() && ::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return {};
}

// A private folder removed with everything in it (the browser's profile too).
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("gpm_html_in_browser_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// Runs chromium headless on page.html in dir in a window `width` x 900 px
// with `action` (--dump-dom or --screenshot=FILE); returns its standard output.
std::string run_chromium(const std::string& chromium, const fs::path& dir, int width, const std::string& action) {
  const std::string d = dir.string();
  // HOME and XDG folders point into dir so nothing is written elsewhere.
  const std::string cmd = "HOME='" + d + "' XDG_CONFIG_HOME='" + d + "/config' XDG_CACHE_HOME='" + d +
                          "/cache' timeout 120 '" + chromium +
                          "' --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars "
                          "--user-data-dir='" + d + "/profile' --window-size=" + std::to_string(width) +
                          ",900 " + action + " 'file://" + d + "/page.html' 2>'" + d + "/stderr.txt'";
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    ::pclose(p);
  }
  return out;
}

// The verdict of the measuring script on html at a window width. A
// headless window is at least 500 px wide, so the page is measured in a
// frame of that width (its innerWidth) inside a page that shows the
// frame's verdict, which --dump-dom prints.
std::string verdict(const std::string& chromium, const std::string& html, int width) {
  ScratchDir dir;
  std::string page = html;
  const size_t end = page.rfind("</body>");
  page.insert(end == std::string::npos ? page.size() : end, std::string("<script>") + kCheckScript + "</script>");
  std::ofstream(dir.path / "checked.html") << page;
  std::ofstream(dir.path / "page.html")
      << "<html><body style=\"margin:0\"><pre id=\"verdict\"></pre><script>addEventListener('message', (e) => { "
         "document.getElementById('verdict').textContent = e.data; });</script><iframe src=\"checked.html\" width=\""
      << width << "\" height=\"900\" style=\"border:0;display:block\"></iframe></body></html>";
  const std::string dom = run_chromium(chromium, dir.path, width + 40, "--virtual-time-budget=5000 --dump-dom");
  const size_t a = dom.find("<pre id=\"verdict\">"), b = dom.find("</pre>", a);
  if (a == std::string::npos || b == std::string::npos) {
    std::ifstream err(dir.path / "stderr.txt");
    return "no verdict; chromium said: " + std::string(std::istreambuf_iterator<char>(err), {});
  }
  std::string v = dom.substr(a + 18, b - a - 18);
  for (const auto& [entity, c] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}})
    for (size_t at = v.find(entity); at != std::string::npos; at = v.find(entity, at + 1)) v.replace(at, std::strlen(entity), c);
  return v;
}

class HtmlInBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = find_chromium();
    if (chromium_.empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  }
  std::string chromium_;
};

TEST_F(HtmlInBrowser, RunReportFitsAndDrawsEveryFigure) {
  const ReportDocument d = build_run_report(testing::run_report_example());
  const std::string expected = "figures " + std::to_string(d.figure_files().size()) + "\nOK";
  ASSERT_EQ(d.figure_files().size(), 6u);
  // A desktop window, a narrow one (tables switch to a smaller font) and a
  // phone (tables scroll in their own box, the page never sideways).
  for (int width : {1000, 720, 390}) EXPECT_EQ(verdict(chromium_, d.html("example"), width), expected) << width << " px";
}

TEST_F(HtmlInBrowser, MonitorAndPaperReportsFitAPhone) {
  MonitorReport m;
  m.simulated_s = 60, m.cycle_hz = 1000, m.cycles = 60000, m.chi_threshold = 321.5, m.window = 250;
  m.learning = "learning phase 5.00 s (no alarm before 5.00 s), 5000 samples: innovation scale 1.02";
  m.detections = {{0, 20.0, 20.31, "dth2 jumped by 1.00e-03 rad (estimated 0.000998 rad)"}};
  m.alarms = {{20.31, "step", 40.2, 30.1, "dth2 (step 0.000998 rad, 9.9 sigma)"}};
  for (const char* n : {"xa3", "ya3", "la1", "la2", "la3", "lb1", "lb2", "lb3", "dth1", "dth2", "dth3"})
    m.parameters.push_back({n, 244.123456, 244.123789, 2e-4, 1e3, {0.0, 1e-3, 2e-3}});
  m.track_t_s = {0.0, 30.0, 60.0};
  PaperTable t;
  t.id = "table2";
  t.title = "Table 2. Calibration results of sensor zero positions with generated data";
  t.setup = "Generated data: the paper's nominal mechanism, three samples.";
  t.extra_column = "actual";
  t.rows.push_back({"dth1, J1, 3 samples", "rad", 1.009132, "1.009132", 1.0091324567, "1.00913246", "1.00913246",
                    PaperReason::kPaperMistake, "The printed initial estimates come from the nominal mechanism."});
  const PaperDocument p{20000, 1, 12.0, {t}};
  for (const auto& [name, html] : {std::pair{"monitor", monitor_report("monitor_offset_jump_realistic", m).html("t")},
                                   std::pair{"paper", paper_document(p).html("t")}})
    for (int width : {390}) {  // a phone: the hard case (1280 px fits what 390 px fits)
      const std::string v = verdict(chromium_, html, width);
      EXPECT_NE(v.find("\nOK"), std::string::npos) << name << " at " << width << " px: " << v;
    }
}

TEST_F(HtmlInBrowser, AWideTableScrollsInItsOwnBoxNotThePage) {
  ReportDocument d;
  d.table({"a", "b"}, {{"1", std::string(300, '7')}});
  EXPECT_EQ(verdict(chromium_, d.html("t"), 390), "figures 0\nOK");
}

TEST_F(HtmlInBrowser, CatchesAPageThatScrollsSidewaysAndAnEmptyFigure) {
  // The check must be able to fail: a line too long for any window outside
  // a scrolling box, and a figure drawn with no size.
  ReportDocument d;
  d.paragraph("PLACEHOLDER");
  d.figure("empty", "empty", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"0\" height=\"0\"></svg>");
  std::string html = d.html("t");
  html.replace(html.find("<p>PLACEHOLDER</p>"), 18, "<p style=\"white-space:nowrap\">" + std::string(300, '7') + "</p>");
  const std::string v = verdict(chromium_, html, 1000);
  EXPECT_NE(v.find("page: "), std::string::npos) << v;
  EXPECT_NE(v.find("overflows its box: <p> \"777"), std::string::npos) << v;
  EXPECT_NE(v.find("figure fig-empty: drawn with no size"), std::string::npos) << v;
}

TEST_F(HtmlInBrowser, CatchesALegendClippedByItsFigure) {
  ReportDocument d;
  d.figure("clipped", "clipped",
           "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"100\" viewBox=\"0 0 200 100\">"
           "<text x=\"10\" y=\"50\">inside</text><text x=\"10\" y=\"104\">last legend entry</text></svg>");
  const std::string v = verdict(chromium_, d.html("t"), 1000);
  EXPECT_NE(v.find("figure fig-clipped: clipped <text> \"last legend entry\""), std::string::npos) << v;
  EXPECT_EQ(v.find("\"inside\""), std::string::npos) << v;
}

TEST_F(HtmlInBrowser, ScreenshotIsAPngOfTheWindowWidth) {
  ScratchDir dir;
  std::ofstream(dir.path / "page.html") << build_run_report(testing::run_report_example()).html("example");
  run_chromium(chromium_, dir.path, 1000, "--screenshot='" + (dir.path / "shot.png").string() + "'");
  std::ifstream png(dir.path / "shot.png", std::ios::binary);
  const std::string head((std::istreambuf_iterator<char>(png)), {});
  ASSERT_GE(head.size(), 24u) << "no screenshot";
  EXPECT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height, big-endian, at bytes 16 and 20.
  auto be32 = [&](size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(head[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(head[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(head[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(head[at + 3]));
  };
  EXPECT_EQ(be32(16), 1000u);
  EXPECT_EQ(be32(20), 900u);
  // Not a blank page: a screenshot of tables and text compresses to well over 10 kB.
  EXPECT_GT(head.size(), 10000u);
}

}  // namespace
}  // namespace gpm::report
