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
  if (root.scrollWidth > root.clientWidth + 1)
    bad.push(`page: ${root.scrollWidth} px wide in a ${root.clientWidth} px window`);
  const name = (e) => `<${e.tagName.toLowerCase()}> "${(e.textContent || '').trim().slice(0, 40)}"`;
  const body = document.body.getBoundingClientRect();
  for (const e of document.body.querySelectorAll('*')) {
    if (e instanceof SVGElement && !(e instanceof SVGSVGElement && e.parentElement instanceof HTMLElement)) continue;
    if (!(e instanceof SVGElement) && e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1)
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

// Runs chromium headless on page.html in dir with `action` (--dump-dom or
// --screenshot=FILE); returns its standard output.
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

// The verdict of the measuring script on html at a window width.
std::string verdict(const std::string& chromium, const std::string& html, int width) {
  ScratchDir dir;
  std::string page = html;
  const size_t end = page.rfind("</body>");
  page.insert(end == std::string::npos ? page.size() : end, std::string("<script>") + kCheckScript + "</script>");
  std::ofstream(dir.path / "page.html") << page;
  const std::string dom = run_chromium(chromium, dir.path, width, "--dump-dom");
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
  // A desktop window and a narrow one (tables switch to a smaller font).
  for (int width : {1000, 720}) EXPECT_EQ(verdict(chromium_, d.html("example"), width), expected) << width << " px";
}

TEST_F(HtmlInBrowser, CatchesAnOverflowingTableAndAnEmptyFigure) {
  // The check must be able to fail: a number too long for any window, and a
  // figure drawn with no size.
  ReportDocument d;
  d.table({"a", "b"}, {{"1", std::string(300, '7')}});
  d.figure("empty", "empty", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"0\" height=\"0\"></svg>");
  const std::string v = verdict(chromium_, d.html("t"), 1000);
  EXPECT_NE(v.find("page: "), std::string::npos) << v;
  EXPECT_NE(v.find("sticks out of the page: <table>"), std::string::npos) << v;
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
