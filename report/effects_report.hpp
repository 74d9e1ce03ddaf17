// The report of `gpm study effects`: what each physical effect of the twin
// does to the calibration of each procedure (table, figures and parameter
// errors per procedure), from plain data.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "models/parameters.hpp"
#include "report/report_document.hpp"

namespace gpm::report {

// One procedure calibrated on one effect case.
struct EffectsRow {
  std::string procedure, effect;
  std::optional<std::string> failure;             // refused, diverged or not converged: why
  std::array<double, kNumParams> error{};         // estimated - actual (mm, rad; NaN where fixed)
  std::array<double, kNumParams> crb{};           // Cramer-Rao 1-sigma at the truth (NaN where fixed)
  std::string worst_param;                        // largest |error| (offsets counted at the 244 mm link)
  double worst_error_um = 0.0;                    // its size, um (offsets x 244 mm)
  std::string worst_crb_param;                    // largest |error| / CRB sigma
  double worst_crb_ratio = 0.0;
  double nominal_um = 0.0, calibrated_um = 0.0, floor_um = 0.0;  // static RMS (NaN if not measured)
  double floor_ratio = 0.0;                       // calibrated / floor
  std::optional<bool> model_test_passed;
  std::array<double, 5> motion_nu{};              // skew s2, s3 (s), compliance c1..c3 (rad/N m) when estimated
  std::array<double, 5> motion_nu_sigma{};        // their 1-sigma (NaN where not estimated)
  bool motion_estimated = false;
  double seconds = 0.0;
};

// The realistic values of the effects the study turns on one at a time.
struct RealisticEffects {
  double compliance_rad_per_Nm = 0.0, clearance_um = 0.0, coulomb_Nm = 0.0, viscous_Nm_s = 0.0;
  double expansion_per_K = 0.0, rise_K = 0.0, thermal_time_constant_s = 0.0;
  double encoder_cyclic_rad = 0.0, skew2_s = 0.0, skew3_s = 0.0;
};

// One calibration procedure of the study.
struct EffectsProcedure {
  std::string name, description;
  std::vector<int> free;  // the parameters it estimates
};

// Everything the effects report shows.
struct EffectsReport {
  RealisticEffects realistic;
  std::vector<EffectsProcedure> procedures;
  std::vector<std::string> cases;  // effect case names
  std::vector<EffectsRow> rows;    // procedure-major: rows[p * cases.size() + c]
  double seconds = 0.0;
};

// The table's header.
std::vector<std::string> effects_table_header();

// The table's rows, one per procedure and effect.
std::vector<std::vector<std::string>> effects_table_rows(const std::vector<EffectsRow>& rows);

// The table in Markdown (for the terminal).
std::string effects_markdown_table(const std::vector<EffectsRow>& rows);

// The report: the effects and procedures, the table, three figures and the parameter errors per procedure.
ReportDocument effects_report(const EffectsReport& e);

}  // namespace gpm::report
