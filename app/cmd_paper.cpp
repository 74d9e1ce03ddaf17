// gpm paper: every experiment of the paper run as the paper ran it, written
// as DIR/paper.md, paper.html (figures beside) and paper.json: the printed
// values beside this run's, and why each differs (run/paper/).

#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/number_options.hpp"
#include "app/progress_mode.hpp"
#include "app/written_files.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "run/paper/paper_document.hpp"
#include "run/paper/paper_run.hpp"

namespace gpm::cli {

namespace {

struct PaperArgs {
  std::string out_dir;
  double budget = 5e6;
  unsigned long long seed = 1;
  int jobs = 0;
  std::string progress;  // --progress (app/progress_mode.hpp)
};

void run_paper_command(const PaperArgs& a) {
  if (a.jobs < 0) throw InputError(fmt::format("--jobs: {} is negative (0 = all cores)", a.jobs));
  paper::PaperSettings s;
  s.budget = static_cast<long>(a.budget);
  s.seed = a.seed;
  s.parallel_runs = a.jobs;
  OutputFolder out(a.out_dir);  // a bad folder fails before the runs; all files or none
  const auto status = StatusReporter::on_stderr("gpm paper", progress_mode(a.progress));
  const paper::PaperProgress progress = [&status](const std::string& stage, double f) {
    status->update(f > 0 ? fmt::format("{} {:.0f}%", stage, 100 * f) : stage);
  };
  const paper::PaperRun run = paper::run_paper(s, progress);
  status->finish();
  paper::stage_paper(run, out);
  out.commit();
  int rows = 0, agree = 0;
  for (const auto& t : run.tables) {
    for (const auto& r : t.rows) {
      ++rows;
      agree += r.reason == paper::Reason::kAgrees;
    }
  }
  std::printf("%s", fmt::format("gpm paper: {} tables and figures, {} rows ({} agree, {} differ, each explained) "
                                "in {:.0f} s\n",
                                run.tables.size(), rows, agree, rows - agree, run.seconds)
                        .c_str());
  std::fflush(stdout);
  print_written(a.out_dir);  // paper.md, paper.html, paper.json and the figures
}

}  // namespace

void add_paper(CLI::App& app) {
  auto args = std::make_shared<PaperArgs>();
  auto* cmd = app.add_subcommand("paper", "Run every experiment of the paper; its tables beside this run's");
  cmd->add_option("-o,--out", args->out_dir, "Output directory (paper.md, paper.html, paper.json)")->required();
  cmd->add_option("--budget", args->budget,
                  "Evaluations of the error function per GA/PSO/DE run (the paper's: 5e7)")
      ->capture_default_str()
      ->transform(number_in(limits::kEvaluations));
  cmd->add_option("--seed", args->seed, "Seed of every stochastic run")->capture_default_str()->transform(number_in(limits::kSeed));
  cmd->add_option("-j,--jobs", args->jobs, "GA/PSO/DE runs at once (0 = all cores); results do not depend on it")
      ->capture_default_str();
  add_progress_option(cmd, args->progress);
  cmd->callback([args] { run_paper_command(*args); });
}

}  // namespace gpm::cli
