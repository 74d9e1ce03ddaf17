#include "report/design_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "report/svg_plot.hpp"

namespace gpm::report {
namespace {

// The worst parameter's name, or `none` when there is none.
std::string worst_name(const DesignLayout& l, const char* none) {
  return l.worst_param >= 0 ? std::string(param_name(l.worst_param)) : none;
}

// The table's cells of one layout; best_worst is the optimised layout's worst bound.
std::vector<std::string> layout_cells(const DesignLayout& l, double best_worst) {
  return {l.name, design_bound_text(l.worst_mm), worst_name(l, "-"), design_bound_text(l.mean_mm),
          design_bound_text(l.worst_mm / best_worst), fmt::format("{:.2f}", l.log_det)};
}

// The settings of the comparison and how to read its bounds.
std::string settings_paragraph(const DesignComparison& c) {
  return fmt::format(
      "{} poses each, encoder noise {} rad (1-sigma, iid), free parameters {} (the rest fixed). "
      "Bounds are Cramer-Rao bounds (calib/crb.hpp) at the geometry of `{}` (the nominal one, known before "
      "calibration). mm parameters in mm; encoder offsets dth_i as rad x la_i (the elbow displacement an "
      "offset error causes), so that all compare in mm. worst = largest bound, mean = mean over the free "
      "parameters.",
      c.count, c.sigma, format_param_list(c.free), c.model);
}

// The report's text and table (figures added by design_comparison_report).
ReportDocument comparison_text(const DesignComparison& c) {
  ReportDocument doc;
  doc.heading(1, "Excitation design: layouts at equal poses and noise");
  doc.paragraph(settings_paragraph(c));
  std::vector<std::vector<std::string>> table;
  for (const auto& l : c.layouts) table.push_back(layout_cells(l, c.layouts.back().worst_mm));
  doc.table({"layout", "worst bound (mm)", "worst parameter", "mean bound (mm)", "worst / optimised", "log det F"},
            table);
  doc.paragraph("Layouts:");
  std::vector<std::string> layouts;
  for (const auto& l : c.layouts) layouts.push_back(fmt::format("`{}`: {}", l.name, l.description));
  doc.bullets(layouts);
  doc.paragraph(fmt::format("The optimised set is {:.1f}x better on the worst-parameter bound than the best of "
                            "the others (goal: at least 3x).", c.improvement));
  return doc;
}

// One line per layout of every free parameter's finite bound, on a log axis.
std::string bounds_figure(const DesignComparison& c) {
  std::vector<Series> series;
  PlotOptions po = titled_plot(fmt::format("Cramer-Rao bound per parameter, {} poses, noise {} rad", c.count, c.sigma),
                               "free parameter (offsets as rad x la)", "1-sigma bound (mm)");
  po.log_y = true;
  po.width = 760;
  for (int i : c.layouts.front().free_index) po.x_categories.emplace_back(param_name(i));
  for (const auto& l : c.layouts) {
    Series s;
    s.label = l.name;
    s.style = Series::Style::kLineMarkers;
    for (Eigen::Index k = 0; k < l.scaled.size(); ++k)
      if (std::isfinite(l.scaled[k])) s.x.push_back(static_cast<double>(k)), s.y.push_back(l.scaled[k]);
    series.push_back(std::move(s));
  }
  return svg_plot(series, po);
}

// The poses of every layout in the workspace, at equal scale on x and y.
std::string layouts_figure(const DesignComparison& c) {
  std::vector<Series> series;
  PlotOptions po = workspace_plot("Pose layouts in the workspace");
  po.width = 640;
  po.height = 640;
  for (const auto& l : c.layouts) {
    Series s;
    s.label = l.name;
    s.style = Series::Style::kMarkers;
    for (const auto& p : l.poses) s.x.push_back(p.x()), s.y.push_back(p.y());
    series.push_back(std::move(s));
  }
  return svg_plot(series, po);
}

}  // namespace

std::string design_bound_text(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "inf"; }

ReportDocument design_comparison_report(const DesignComparison& c) {
  ReportDocument doc = comparison_text(c);
  doc.heading(2, "Figures");
  doc.figure("design_comparison", "Cramer-Rao bound of every free parameter, per layout", bounds_figure(c));
  doc.figure("design_layouts", "The poses of every layout", layouts_figure(c));
  return doc;
}

std::string design_comparison_csv(const DesignComparison& c) {
  std::string csv = "layout,poses,worst_mm,worst_param,mean_mm,log_det";
  for (int i : c.layouts.front().free_index) csv += fmt::format(",{}_mm", param_name(i));
  csv += "\n";
  for (const auto& l : c.layouts) {
    csv += fmt::format("{},{},{},{},{},{}", l.name, l.poses.size(), l.worst_mm, worst_name(l, ""), l.mean_mm,
                       l.log_det);
    for (Eigen::Index k = 0; k < l.scaled.size(); ++k) csv += fmt::format(",{}", l.scaled[k]);
    csv += "\n";
  }
  return csv;
}

}  // namespace gpm::report
