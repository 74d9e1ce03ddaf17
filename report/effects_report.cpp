#include "report/effects_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"

namespace gpm::report {
namespace {

constexpr auto cell = table_cell;

// Figure: one value per case (x: the cases), one marker series per procedure.
std::string per_case_plot(const EffectsReport& e, double EffectsRow::*field, const std::string& title,
                          const std::string& y_label) {
  std::vector<Series> series;
  const size_t nc = e.cases.size();
  for (size_t p = 0; p < e.procedures.size(); ++p) {
    Series ser;
    ser.label = e.procedures[p].name;
    ser.style = Series::Style::kMarkers;
    for (size_t c = 0; c < nc; ++c) {
      const double v = e.rows[p * nc + c].*field;
      if (!std::isfinite(v)) continue;
      ser.x.push_back(static_cast<double>(c));
      ser.y.push_back(v);
    }
    series.push_back(ser);
  }
  PlotOptions po = titled_plot(title, "effect (alone at its realistic value; all: every one)", y_label);
  po.log_y = true;
  po.width = 720;
  po.x_categories = e.cases;
  return svg_plot(series, po);
}

// The paragraph saying which effects, at which values, and how the runs are judged.
std::string effects_paragraph(const RealisticEffects& fx) {
  return fmt::format(
      "Each effect of the realistic twin alone at its realistic value (transmission compliance {:g} rad/N m, "
      "passive clearance {:g} µm, friction {:g} N m + {:g} N m s/rad, thermal {:g}/K x {:g} K with time constant "
      "{:g} s, encoder cyclic error {:g} rad, encoder latch skew {:g} / {:g} s), all of them together, and none "
      "(ideal); then the geared machine's effects the preset leaves out, drawn once from their plausible ranges "
      "behind a 10:1 reducer (drive_train, encoder_motor), and with the preset (every); all on the same actual "
      "robot (the scenario's seed) for each procedure. Errors are estimated minus "
      "actual; offsets are counted in µm at the 244 mm link. The floor is the static RMS error of the controller "
      "given the actual parameters on the same twin; calibrated / floor is what the calibration leaves on the "
      "table. CRB sigma: the Cramer-Rao bound the run reports (on the fly: jointly with the nuisance values it "
      "estimates, and carrying the encoders' cyclic error with its data-sheet prior; stop-and-go: for the encoder "
      "quantisation and noise alone).",
      fx.compliance_rad_per_Nm, fx.clearance_um, fx.coulomb_Nm, fx.viscous_Nm_s, fx.expansion_per_K, fx.rise_K,
      fx.thermal_time_constant_s, fx.encoder_cyclic_rad, fx.skew2_s, fx.skew3_s);
}

// The parameter errors of procedure p on every case (um, urad for offsets).
void add_parameter_errors(ReportDocument& doc, const EffectsReport& e, size_t p) {
  const EffectsProcedure& proc = e.procedures[p];
  doc.heading(2, fmt::format("Parameter errors: {}", proc.name));
  std::vector<std::string> header{"effect"};
  for (int k : proc.free) header.push_back(fmt::format("{} ({})", param_name(k), is_offset(k) ? "urad" : "um"));
  std::vector<std::vector<std::string>> rows;
  const size_t nc = e.cases.size();
  for (size_t c = 0; c < nc; ++c) {
    const EffectsRow& r = e.rows[p * nc + c];
    std::vector<std::string> row{r.effect};
    for (int k : proc.free)
      row.push_back(cell(r.error[static_cast<size_t>(k)] * 1e3 * (is_offset(k) ? 1e3 : 1.0), "{:.1f}"));
    rows.push_back(row);
  }
  doc.table(header, rows);
}

}  // namespace

std::vector<std::string> effects_table_header() {
  return {"procedure", "effect", "worst parameter", "its error (um)", "worst error / CRB sigma",
          "calibrated static RMS (um)", "floor (um)", "calibrated / floor", "model test"};
}

std::vector<std::vector<std::string>> effects_table_rows(const std::vector<EffectsRow>& rows) {
  std::vector<std::vector<std::string>> out;
  for (const EffectsRow& r : rows) {
    const std::string test = r.model_test_passed ? (*r.model_test_passed ? "passes" : "fails") : "-";
    out.push_back({r.procedure, r.effect, r.worst_param.empty() ? "-" : r.worst_param,
                   cell(r.worst_error_um, "{:.1f}"),
                   r.worst_crb_param.empty() ? "-"
                                             : fmt::format("{} ({})", cell(r.worst_crb_ratio, "{:.3g}"), r.worst_crb_param),
                   cell(r.calibrated_um, "{:.1f}"), cell(r.floor_um, "{:.1f}"), cell(r.floor_ratio, "{:.2f}"),
                   r.failure ? fmt::format("{} ({})", test, *r.failure) : test});
  }
  return out;
}

std::string effects_markdown_table(const std::vector<EffectsRow>& rows) {
  ReportDocument table;  // the report's own Markdown table
  table.table(effects_table_header(), effects_table_rows(rows));
  return table.markdown();
}

ReportDocument effects_report(const EffectsReport& e) {
  ReportDocument doc;
  doc.heading(1, "What each physical effect does to calibration");
  doc.paragraph(effects_paragraph(e.realistic));
  std::vector<std::string> procs;
  for (const EffectsProcedure& p : e.procedures) procs.push_back(fmt::format("{}: {}", p.name, p.description));
  doc.bullets(procs);
  doc.table(effects_table_header(), effects_table_rows(e.rows));
  doc.figure("effects_floor_ratio", "Static RMS error after calibration over the floor, per effect and procedure",
             per_case_plot(e, &EffectsRow::floor_ratio, "calibrated / floor (static RMS)", "calibrated / floor"));
  doc.figure("effects_crb_ratio", "Largest parameter error in Cramer-Rao sigmas, per effect and procedure",
             per_case_plot(e, &EffectsRow::worst_crb_ratio, "worst parameter error / CRB sigma", "error / CRB sigma"));
  doc.figure("effects_worst_error", "Largest parameter error (offsets x 244 mm), per effect and procedure",
             per_case_plot(e, &EffectsRow::worst_error_um, "worst parameter error", "um"));
  for (size_t p = 0; p < e.procedures.size(); ++p) add_parameter_errors(doc, e, p);
  doc.paragraph(fmt::format("{} runs in {:.0f} s.", e.rows.size(), e.seconds));
  return doc;
}

}  // namespace gpm::report
