// Tests of run/effects_study.cpp: a reduced study (ideal and compliance, 20
// poses, both procedures) through the runner; the table, the JSON and the
// report agree; the effect moves the results in the physically expected
// direction; the full study (label long) runs every case.
#include "run/effects_study.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "models/errors.hpp"
#include "models/output_file.hpp"

namespace gpm::scenario {
namespace {

namespace fs = std::filesystem;

const EffectsRow& row(const EffectsStudy& s, const std::string& procedure, const std::string& effect) {
  for (const EffectsRow& r : s.rows)
    if (r.procedure == procedure && r.effect == effect) return r;
  throw std::runtime_error("no row " + procedure + " / " + effect);
}

// The reduced study is shared by the tests below (about 4 runs of a few seconds).
const EffectsStudy& reduced_study() {
  static const EffectsStudy study = [] {
    EffectsStudyOptions o;
    o.cases = {EffectCase::kIdeal, EffectCase::kCompliance};
    o.sample_count = 20;
    o.compensation_count = 6;
    o.path_revolutions = 0.25;
    return run_effects_study(default_study_procedures(), o);
  }();
  return study;
}

TEST(EffectCases, NamesRoundTripAndEachCaseSwitchesOnlyItsEffect) {
  const sim::Effects real = sim::realistic_effects();
  for (EffectCase c : all_effect_cases()) {
    EXPECT_EQ(parse_effect_case(effect_case_name(c)), c);
    const sim::Effects e = effects_for_case(c, real);
    EXPECT_EQ(e.any(), c != EffectCase::kIdeal) << effect_case_name(c);
  }
  EXPECT_FALSE(parse_effect_case("stiffness"));
  const sim::Effects comp = effects_for_case(EffectCase::kCompliance, real);
  EXPECT_EQ(comp.mjcf.compliance_rad_per_Nm, real.mjcf.compliance_rad_per_Nm);
  EXPECT_EQ(comp.mjcf.clearance_m[0], 0.0);
  EXPECT_FALSE(comp.thermal.on());
  const sim::Effects skew = effects_for_case(EffectCase::kEncoderSkew, real);
  EXPECT_EQ(skew.encoder_skew_s, real.encoder_skew_s);
  EXPECT_EQ(skew.mjcf.compliance_rad_per_Nm[1], 0.0);
  EXPECT_EQ(skew.encoder_cyclic_rad[2], 0.0);
  // The geared machine's effects: each alone, and with the preset in `every`.
  const sim::Effects drive = effects_for_case(EffectCase::kDriveTrain, real);
  EXPECT_TRUE(drive.drive.any());
  EXPECT_FALSE(drive.encoder_and_geometry_on());
  EXPECT_EQ(drive.mjcf.coulomb_Nm[0], 0.0);
  const sim::Effects motor = effects_for_case(EffectCase::kEncoderMotor, real);
  EXPECT_TRUE(motor.encoder_and_geometry_on());
  EXPECT_FALSE(motor.drive.any());
  EXPECT_EQ(motor.gear_ratio, 10.0);
  const sim::Effects every = effects_for_case(EffectCase::kEvery, real);
  EXPECT_TRUE(every.drive.any() && every.encoder_and_geometry_on());
  EXPECT_EQ(every.mjcf.coulomb_Nm, real.mjcf.coulomb_Nm);
}

TEST(EffectsStudy, RefusesTooFewPoses) {
  EffectsStudyOptions o;
  o.sample_count = 5;
  EXPECT_THROW(run_effects_study(default_study_procedures(), o), InputError);
}

TEST(EffectsStudy, ComplianceUnderThreePositionDrivesBiasesTheDiscProcedure) {
  const EffectsStudy& s = reduced_study();
  ASSERT_EQ(s.rows.size(), 4u);
  for (const EffectsRow& r : s.rows) {
    EXPECT_FALSE(r.failure) << r.procedure << " " << r.effect << ": " << r.failure.value_or("");
    EXPECT_GT(r.floor_um, 0.0);
    // Calibration beats the nominal model by far in every case.
    EXPECT_LT(r.calibrated_um, r.nominal_um / 10.0) << r.procedure << " " << r.effect;
  }
  // Stop-and-go with three position drives: the fighting drives' preload
  // twists each transmission by compliance x torque, which the readings do not
  // see, so the identified offsets and lengths are biased: the worst error in
  // Cramer-Rao sigmas and the accuracy after calibration both get worse.
  const EffectsRow& disc_ideal = row(s, "disc stop-and-go", "ideal");
  const EffectsRow& disc_comp = row(s, "disc stop-and-go", "compliance");
  EXPECT_GT(disc_comp.floor_ratio, 3.0 * disc_ideal.floor_ratio);
  EXPECT_GT(disc_comp.worst_crb_ratio, 3.0 * disc_ideal.worst_crb_ratio);
  // On the fly the compliance is estimated with the geometry (and joint 1 is
  // torque-off): the same compliance costs far less.
  const EffectsRow& fly_comp = row(s, "on the fly", "compliance");
  EXPECT_LT(fly_comp.floor_ratio, disc_comp.floor_ratio / 10.0);
  ASSERT_TRUE(fly_comp.motion_estimated);
  // The estimated compliance of the driven chains 2 and 3 is the twin's
  // 1e-4 rad/N m within a factor 2 with 20 poses (chain 1 is torque-off: not
  // excited); without the effect it is under a third of that. (With the
  // joint speeds differentiated from the readings, calib/reading_rates.hpp,
  // the ideal twin gives 2.0e-5 and 2.6e-5 at 6 of their sigmas: something
  // that follows the drive torque, not yet explained, is in the readings.)
  const EffectsRow& fly_ideal = row(s, "on the fly", "ideal");
  for (size_t i = 3; i < 5; ++i) {
    EXPECT_GT(fly_comp.motion_nu[i], 0.5e-4) << i;
    EXPECT_LT(fly_comp.motion_nu[i], 2e-4) << i;
    EXPECT_LT(std::abs(fly_ideal.motion_nu[i]), 0.33e-4) << i << " sigma " << fly_ideal.motion_nu_sigma[i];
  }
}

TEST(EffectsStudy, TableJsonAndReportAgree) {
  const EffectsStudy& s = reduced_study();
  const nlohmann::json j = nlohmann::json::parse(effects_json(s));
  const auto table = effects_table_rows(s);
  ASSERT_EQ(j["rows"].size(), table.size());
  const auto header = effects_table_header();
  const auto col = [&](const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (size_t k = 0; k < table.size(); ++k) {
    const auto& jr = j["rows"][k];
    const auto& tr = table[k];
    EXPECT_EQ(tr[col("procedure")], jr["procedure"].get<std::string>());
    EXPECT_EQ(tr[col("effect")], jr["effect"].get<std::string>());
    EXPECT_EQ(tr[col("worst parameter")], jr["worst_parameter"].get<std::string>());
    // Printed to 0.1 um / 0.01: agree to the printed precision.
    EXPECT_NEAR(std::stod(tr[col("its error (um)")]), jr["worst_error_um"].get<double>(), 0.051);
    EXPECT_NEAR(std::stod(tr[col("calibrated / floor")]), jr["floor_ratio"].get<double>(), 0.0051);
    const double cal = jr["static_rms_um"]["calibrated"].get<double>();
    const double flo = jr["static_rms_um"]["actual"].get<double>();
    EXPECT_NEAR(std::stod(tr[col("calibrated static RMS (um)")]), cal, 0.051);
    EXPECT_NEAR(cal / flo, jr["floor_ratio"].get<double>(), 1e-12);
    // The worst parameter of the JSON is the largest of its 11 errors.
    ASSERT_EQ(jr["parameters"].size(), 11u);
    double worst = 0.0;
    std::string worst_name;
    for (const auto& [name, p] : jr["parameters"].items()) {
      const bool offset = name.rfind("dth", 0) == 0;
      const double um = std::abs(p["error"].get<double>()) * (offset ? 244.0 : 1.0) * 1e3;
      if (um > worst) worst = um, worst_name = name;
    }
    EXPECT_EQ(worst_name, jr["worst_parameter"].get<std::string>());
    EXPECT_NEAR(worst, jr["worst_error_um"].get<double>(), 1e-9 * worst);
  }
  // The Markdown report holds the summary table and names every figure it writes.
  const report::ReportDocument doc = effects_report(s);
  const std::string md = doc.markdown();
  EXPECT_NE(md.find(effects_markdown_table(s)), std::string::npos);
  for (const auto& [file, svg] : doc.figure_files()) {
    EXPECT_NE(md.find("(" + file + ")"), std::string::npos) << file;
    EXPECT_EQ(svg.rfind("<svg", 0), 0u) << file;
  }
  EXPECT_EQ(doc.figure_files().size(), 3u);
}

TEST(EffectsStudy, WritesEveryFileOrNone) {
  const EffectsStudy& s = reduced_study();
  const fs::path dir = fs::path(::testing::TempDir()) / "gpm_effects_study_test";
  fs::remove_all(dir);
  write_effects_study(s, dir.string());
  for (const char* f : {"effects.md", "effects.html", "effects.json", "effects_floor_ratio.svg",
                        "effects_crb_ratio.svg", "effects_worst_error.svg"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  std::ifstream in(dir / "effects.json");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), effects_json(s));
  fs::remove_all(dir);
  // Over a file: refused, nothing written.
  { std::ofstream(dir.string()) << "x"; }
  EXPECT_THROW(write_effects_study(s, dir.string()), InputError);
  fs::remove(dir);
}

// The full study (every case, each procedure's own pose count): label long.
TEST(EffectsStudyLong, DISABLED_EveryEffectAloneAndAll) {
  const EffectsStudy s = run_effects_study(default_study_procedures(), EffectsStudyOptions{});
  ASSERT_EQ(s.rows.size(), 2 * all_effect_cases().size());
  for (const EffectsRow& r : s.rows) {
    EXPECT_FALSE(r.failure) << r.procedure << " " << r.effect << ": " << r.failure.value_or("");
    EXPECT_LT(r.calibrated_um, r.nominal_um / 10.0) << r.procedure << " " << r.effect;
  }
  // Every effect together biases the former procedure far more than today's.
  EXPECT_GT(row(s, "disc stop-and-go", "all").floor_ratio, 3.0 * row(s, "on the fly", "all").floor_ratio);
  EXPECT_GT(row(s, "disc stop-and-go", "all").floor_ratio, 3.0 * row(s, "disc stop-and-go", "ideal").floor_ratio);
}

}  // namespace
}  // namespace gpm::scenario
