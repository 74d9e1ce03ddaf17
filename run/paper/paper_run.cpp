#include "run/paper/paper_run.hpp"

#include <chrono>

#include "models/errors.hpp"
#include "run/paper/section2_table.hpp"
#include "run/paper/section3_tables.hpp"
#include "run/paper/section4_tables.hpp"

namespace gpm::paper {

PaperRun run_paper(const PaperSettings& settings, const PaperProgress& progress) {
  if (settings.budget < 1) throw InputError("--budget: must be at least 1 evaluation (the paper's is 5e7)");
  if (settings.table8_evaluations < 1) throw InputError("table 8: evaluations must be at least 1");
  const auto t0 = std::chrono::steady_clock::now();
  const auto stage = [&](const std::string& s, double f) {
    if (progress) progress(s, f);
  };
  PaperRun run;
  run.settings = settings;
  stage("Table 1 (section 2.4 search on the twin)", 0.0);
  Table1Settings t1;
  t1.circle_points = settings.zero_circle_points;
  t1.d_min_mm = settings.zero_d_min_mm;
  t1.on_experiment = [&](int k) { stage("Table 1 (section 2.4 search on the twin)", (k - 1) / 3.0); };
  run.tables.push_back(table1(t1));
  stage("Tables 2-4 (section 3.3, LM)", 0.0);
  run.tables.push_back(table2());
  run.tables.push_back(table3());
  run.tables.push_back(table4());
  stage("Tables 5-7, Figures 3-5 (GA, PSO, DE)", 0.0);
  Section4Settings s4;
  s4.budget = settings.budget;
  s4.seed = settings.seed;
  s4.parallel_runs = settings.parallel_runs;
  const Section4Tables s = section4_tables(s4, [&](long done, long total) {
    stage("Tables 5-7, Figures 3-5 (GA, PSO, DE)", static_cast<double>(done) / static_cast<double>(total));
  });
  run.tables.push_back(s.table5);
  run.tables.push_back(s.table6);
  run.tables.push_back(s.figure3);
  run.tables.push_back(s.figure4);
  run.tables.push_back(s.figure5);
  run.tables.push_back(s.table7);
  stage("Table 8 (DE on the twin's readings)", 0.0);
  run.tables.push_back(table8(settings.table8_evaluations, settings.seed));
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

}  // namespace gpm::paper
