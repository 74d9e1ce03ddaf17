// gpm compare: equal-budget comparison of GA, PSO and DE on J1, J2, J3 with
// simulated Table 5 data (paper section 4.4): writes a Table 6 in markdown,
// CSVs of every run and history, and log10(J) figures (SVG) into a directory.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/number_options.hpp"
#include "app/written_files.hpp"
#include "calib/global/comparison.hpp"
#include "calib/paper_values.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "report/compare_report.hpp"
#include "run/compare_report_data.hpp"

namespace gpm::cli {

namespace {

struct CompareArgs {
  std::string out_dir;
  long budget = 1'500'000;  // bounded by its validator (limits::kEvaluations)
  std::string seeds = "1,2,3";
  int gauge = 12;
  int samples = 50;
  uint64_t data_seed = 42;
  std::string methods = "ga,pso,de";
  std::string costs = "j1,j2,j3";
  int jobs = 0;
};

void run_compare(const CompareArgs& a) {
  calib::global::ComparisonSettings st;
  st.budget = a.budget;
  st.samples = a.samples;
  st.data_seed = a.data_seed;
  st.parallel_runs = a.jobs;
  if (a.gauge == 12) st.free = calib::paper_free_mask();
  else if (a.gauge == 11) st.free = default_free_mask();
  else throw InputError(fmt::format("--gauge: {} is not 11 or 12", a.gauge));
  st.seeds.clear();
  for (const auto& s : split_unique_list(a.seeds, "--seeds"))
    st.seeds.push_back(static_cast<uint64_t>(parse_bounded(s, limits::kSeed, "--seeds")));
  st.methods.clear();
  for (const auto& s : split_unique_list(a.methods, "--methods")) {
    const calib::Method m = calib::parse_method(s, "--methods");
    if (m == calib::Method::kLM || m == calib::Method::kDELM)
      throw InputError(fmt::format("--methods: '{}' is not ga, pso or de", s));
    st.methods.push_back(m);
  }
  st.costs.clear();
  for (const auto& s : split_unique_list(a.costs, "--costs")) {
    const auto c = calib::parse_cost(s);
    if (!c || *c == calib::Cost::kML) throw InputError(fmt::format("--costs: '{}' is not j1, j2 or j3", s));
    st.costs.push_back(*c);
  }
  // All files or none (models/output_file.hpp); a bad folder fails before the runs.
  OutputFolder out(a.out_dir);

  calib::global::ComparisonProgress progress;
  if (isatty(STDERR_FILENO)) {
    progress = [](long done, long total, int runs_done, int runs) {
      std::fprintf(stderr, "\rgpm compare: %5.1f%% of %.3g evaluations, %d of %d runs done ",
                   100.0 * static_cast<double>(done) / static_cast<double>(total),
                   static_cast<double>(total), runs_done, runs);
      std::fflush(stderr);
    };
  }
  const auto c = calib::global::run_comparison(st, progress);
  if (progress) std::fprintf(stderr, "\n");

  const report::CompareReport data = scenario::compare_report_data(c);
  out.add("table6.md", report::compare_markdown(data));
  out.add("runs.csv", calib::global::comparison_runs_csv(c));
  out.add("history.csv", calib::global::comparison_history_csv(c));
  for (calib::Cost cost : st.costs)
    out.add(fmt::format("convergence_{}.svg", calib::cost_name(cost)), report::compare_svg(data, std::string(calib::cost_name(cost))));
  out.commit();
  std::printf("%s", fmt::format("gpm compare: {} runs in {:.1f} s\n{}\n", c.runs.size(), c.seconds,
                                c.at_actual.diagnosis)
                        .c_str());
  std::fflush(stdout);
  print_written(a.out_dir);  // table6.md, runs.csv, history.csv, convergence_*.svg
}

}  // namespace

void add_compare(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand(
      "compare", "Compare GA, PSO and DE on J1, J2, J3 at equal budget (paper section 4.4)");
  cmd->add_option("-o,--out", args->out_dir, "Output directory")->required();
  cmd->add_option("--budget", args->budget,
                  "Evaluations of the error function per run (the paper used 5e7)")
      ->capture_default_str()
      ->transform(number_in(limits::kEvaluations));
  cmd->add_option("--seeds", args->seeds, "Comma-separated seeds; each method and cost runs once per seed")
      ->capture_default_str();
  cmd->add_option("--gauge", args->gauge,
                  "12: the paper's free set (xa1, ya1, xa2 fixed; rank-deficient), "
                  "11: xa1, ya1, xa2, ya2 fixed (identifiable)")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples, "Random workspace samples")->capture_default_str()->transform(number_in(limits::kSamples));
  cmd->add_option("--data-seed", args->data_seed, "Seed of the sample points")->capture_default_str()->transform(number_in(limits::kSeed));
  cmd->add_option("--methods", args->methods, "Subset of ga,pso,de")->capture_default_str();
  cmd->add_option("--costs", args->costs, "Subset of j1,j2,j3")->capture_default_str();
  cmd->add_option("-j,--jobs", args->jobs, "Runs at once (0 = all cores); results do not depend on it")
      ->capture_default_str();
  cmd->callback([args] { run_compare(*args); });
}

}  // namespace gpm::cli
