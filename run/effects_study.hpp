// `gpm study effects`: what each physical effect of the realistic twin
// (sim/effects.hpp) does to calibration. Every effect alone at its realistic
// value, all together, and none (the reference), each run through the runner
// (run/runner.hpp) for several procedures on the same actual robot (the
// scenario's seed): the error of the identified parameters (also in
// Cramer-Rao sigmas) and the static accuracy after calibration against the
// floor (the controller given the actual parameters).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "models/parameters.hpp"
#include "report/effects_report.hpp"
#include "report/report_document.hpp"
#include "run/run_spec.hpp"
#include "sim/effects.hpp"

namespace gpm::scenario {

// Which effects of the realistic preset are on in one case.
// kDriveTrain, kEncoderMotor: the geared machine's effects the preset leaves
// out, at values drawn once from their plausible ranges (kDrawSeed); kEvery:
// the preset and both.
enum class EffectCase {
  kIdeal, kCompliance, kClearance, kFriction, kThermal, kEncoderCyclic, kEncoderSkew, kAll,
  kDriveTrain, kEncoderMotor, kEvery
};

// Seed of the one draw of the drive train and of the motor encoder's effects.
inline constexpr std::uint64_t kDrawSeed = 1;

// Every case, ideal first and all last (the study's default).
std::vector<EffectCase> all_effect_cases();

// Name of a case as on the command line and in the table ("ideal",
// "compliance", ..., "all").
std::string effect_case_name(EffectCase c);

// Parses a name of effect_case_name; nullopt if it is none of them.
std::optional<EffectCase> parse_effect_case(const std::string& name);

// The effects of case c: the part of `realistic` that c names, every other
// effect off (drive_train, encoder_motor: drawn with kDrawSeed behind a 10:1
// reducer; every: all of it). The encoder phases of `realistic` are kept
// (seeded by the scenario).
sim::Effects effects_for_case(EffectCase c, const sim::Effects& realistic);

// One calibration procedure of the study: a run spec (its effects replaced case by case).
struct StudyProcedure {
  std::string name;         // short, for tables ("on the fly", "disc stop-and-go")
  std::string description;  // one sentence
  std::string scenario;     // the scenario file it was read from
  RunSpec spec;
};

// Today's default procedure (scenarios/main.yaml: designed poses sampled on
// the fly, joint 1 torque-off, compliance and skew estimated) and the former
// default (scenarios/procedure_disc_stopgo_realistic.yaml: random disc,
// stop-and-go, three position drives), both from gpm::scenarios_dir().
// Throws InputError if a file is missing or invalid.
std::vector<StudyProcedure> default_study_procedures();

struct EffectsStudyOptions {
  std::vector<EffectCase> cases = all_effect_cases();
  std::optional<int> sample_count;        // overrides every procedure's sampling count
  std::optional<int> compensation_count;  // keeps only the first N accuracy test poses
  std::optional<double> path_revolutions; // shortens a circular accuracy test path
  int threads = 2;                        // runs in parallel (each case is independent)
};

// The outcome of one (procedure, effect) case.
using EffectsRow = report::EffectsRow;  // report/effects_report.hpp

struct EffectsStudy {
  std::vector<StudyProcedure> procedures;
  std::vector<EffectCase> cases;
  std::vector<EffectsRow> rows;  // procedure-major: rows[p * cases.size() + c]
  double seconds = 0.0;
};

// Called once per finished case (from the thread that ran it, serialised).
using EffectsProgress = std::function<void(const EffectsRow&)>;

// Runs every case of every procedure. A case whose calibration is refused or
// whose simulation fails gives a row with `failure` set; InputError of the
// procedures themselves propagates.
EffectsStudy run_effects_study(const std::vector<StudyProcedure>& procedures, const EffectsStudyOptions& options,
                               const EffectsProgress& progress = {});

// The summary table (one row per case): header and cells as printed.
using report::effects_table_header;
std::vector<std::vector<std::string>> effects_table_rows(const EffectsStudy& study);

// The summary table in Markdown (docs/EFFECTS.md's table is this text).
std::string effects_markdown_table(const EffectsStudy& study);

// DIR/effects.json: procedures, cases, and per row every number of EffectsRow.
std::string effects_json(const EffectsStudy& study);

// The report: the summary table, the parameter errors per procedure, the figures.
report::ReportDocument effects_report(const EffectsStudy& study);

// Writes DIR/effects.md, effects.html, effects.json and the figures, all or none.
void write_effects_study(const EffectsStudy& study, const std::string& dir);

}  // namespace gpm::scenario
