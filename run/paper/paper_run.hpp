// `gpm paper`: every experiment of the paper run as the paper ran it
// (run/paper/section2_table.hpp, section3_tables.hpp, section4_tables.hpp),
// in the paper's order: Tables 1-8 and Figures 3-5.
//
//   PaperSettings s;  s.budget = 50'000'000;   // the paper's budget
//   PaperRun run = run_paper(s);
//   write_paper(run, "out/paper");             // paper_document.hpp
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "run/paper/paper_table.hpp"

namespace gpm::paper {

struct PaperSettings {
  long budget = 5'000'000;         // evaluations per GA/PSO/DE run of Table 6 (the paper: 5e7)
  long table8_evaluations = 1'000'000;  // DE on the twin's readings (the paper: about 1e6)
  std::uint64_t seed = 1;          // every stochastic run
  int parallel_runs = 0;           // Table 6 runs at once (0 = all cores); results do not depend on it
  // Table 1's search (paper section 2.5: 4 mm down to 0.125 mm); tests shorten it.
  int zero_circle_points = 24;
  double zero_d_min_mm = 0.125;
};

struct PaperRun {
  PaperSettings settings;
  std::vector<Table> tables;       // table1 ... table8 with figure3-5 after table6
  double seconds = 0.0;
};

// Called as each experiment starts (its name) and, during Table 6, with the
// fraction of the evaluations done.
using PaperProgress = std::function<void(const std::string& stage, double fraction)>;

// Runs every experiment. Throws InputError for a budget or evaluation count
// < 1 (before anything runs).
PaperRun run_paper(const PaperSettings& settings, const PaperProgress& progress = {});

}  // namespace gpm::paper
