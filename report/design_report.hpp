// The report of `gpm design --compare`: pose layouts at equal poses and noise
// compared by their Cramer-Rao bounds (table, CSV and figures), from plain data.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"
#include "report/report_document.hpp"

namespace gpm::report {

// One layout of the comparison and its bounds (mm; offsets as rad x la_i).
struct DesignLayout {
  std::string name;         // short key: line, circle80, ..., optimised
  std::string description;  // one line
  std::vector<Eigen::Vector2d> poses;
  std::vector<int> free_index;  // parameter index of each entry of scaled
  Eigen::VectorXd scaled;       // 1-sigma bound per free parameter (mm)
  double worst_mm = 0.0, mean_mm = 0.0, log_det = 0.0;
  int worst_param = -1;         // parameter index of the worst bound; -1: none
};

// Everything the comparison report shows; the optimised layout is the last.
struct DesignComparison {
  std::string model;   // the robot file the bounds are taken at
  int count = 0;       // poses per layout
  double sigma = 0.0;  // encoder noise (rad)
  FreeMask free;
  double improvement = 0.0;  // best other layout's worst bound / the optimised one's
  std::vector<DesignLayout> layouts;
};

// A bound as the table shows it: 4 significant digits, "inf" when not finite.
std::string design_bound_text(double v);

// The comparison report: settings, table, layouts and the figures design_comparison.svg and design_layouts.svg.
ReportDocument design_comparison_report(const DesignComparison& c);

// design_comparison.csv: one row per layout with every free parameter's bound.
std::string design_comparison_csv(const DesignComparison& c);

}  // namespace gpm::report
