// gpm.run: the whole `gpm run` of a scenario (run/runner.hpp: the twin, the
// main procedure, compensation, evaluation, the monitor of `operation:`),
// with the GIL released; its summary as summary.json holds it
// (run/summary_json.hpp), parsed by Python's json. Also
// gpm.population_robot_scenario (run/population_study.hpp), the scenario text
// of one robot of a population, which gpm.study runs through gpm.run.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/yaml_util.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/errors.hpp"
#include "run/population_study.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"
#include "run/summary_json.hpp"

namespace gpm::python {
namespace {

namespace fs = std::filesystem;

// A scenario given to gpm.run: a file, or YAML text (a str holding a newline).
struct ScenarioSource {
  bool is_text = false;
  std::string path_or_text;
  std::string label;     // names it in errors and in the run's outputs
  std::string base_dir;  // resolves the relative paths it names
};

// The scenario argument of gpm.run as a file or text; base_dir only with text.
ScenarioSource scenario_source(const py::object& scenario, const py::object& base_dir) {
  ScenarioSource s;
  if (py::isinstance<py::str>(scenario) && scenario.cast<std::string>().find('\n') != std::string::npos) {
    s.is_text = true;
    s.path_or_text = scenario.cast<std::string>();
    s.label = "scenario text";
    s.base_dir = base_dir.is_none() ? fs::current_path().string() : path_arg(base_dir, "base_dir");
    return s;
  }
  if (!base_dir.is_none()) throw InputError("base_dir: only for scenario text (a scenario file's own folder is its base)");
  s.path_or_text = path_arg(scenario, "scenario");
  s.label = s.path_or_text;
  const std::string parent = fs::path(s.path_or_text).parent_path().string();
  s.base_dir = parent.empty() ? "." : parent;
  return s;
}

// A Python value (str, number, bool, list, dict) as a YAML node, through its JSON text.
YAML::Node yaml_of(const py::object& value, const std::string& what) {
  std::string text;
  try {
    text = py::module_::import("json").attr("dumps")(value, py::arg("allow_nan") = false).cast<std::string>();
  } catch (const py::error_already_set& e) {
    throw InputError(fmt::format("{}: not a scenario value (str, number, list or dict): {}", what, e.what()));
  }
  return YAML::Load(text);
}

// The overrides of gpm.run applied to the scenario's YAML (seed, robot,
// effects, sampling.count); their names as "seed=..." for the error label.
std::vector<std::string> apply_overrides(YAML::Node& root, const ScenarioSource& src, const py::object& seed,
                                         const py::object& robot, const py::object& effects,
                                         const py::object& count) {
  std::vector<std::string> names;
  if (!seed.is_none()) {
    if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed))
      throw InputTypeError(fmt::format("seed: expected an integer >= 0, got {}", type_name(seed)));
    root["seed"] = yaml_of(seed, "seed");
    names.push_back("seed=" + py::str(seed).cast<std::string>());
  }
  if (!robot.is_none()) {
    if (py::isinstance<py::dict>(robot)) {
      root["robot"] = yaml_of(robot, "robot");
    } else {  // a file, relative to the caller's working folder
      root["robot"] = fs::absolute(path_arg(robot, "robot")).lexically_normal().string();
    }
    names.push_back("robot");
  }
  if (!effects.is_none()) {
    if (!py::isinstance<py::str>(effects) && !py::isinstance<py::dict>(effects))
      throw InputTypeError("effects: expected a preset name (ideal, realistic, randomized) or a dict of the effects section");
    root["effects"] = yaml_of(effects, "effects");
    names.push_back("effects");
  }
  if (!count.is_none()) {
    if (!py::isinstance<py::int_>(count) || py::isinstance<py::bool_>(count))
      throw InputTypeError(fmt::format("count: expected an integer (sampling.count), got {}", type_name(count)));
    if (!root["sampling"] || !root["sampling"].IsMap())
      throw InputError(fmt::format("count: {} has no sampling section whose count it could set", src.label));
    root["sampling"]["count"] = yaml_of(count, "count");
    names.push_back("count=" + py::str(count).cast<std::string>());
  }
  return names;
}

// The run spec of gpm.run's arguments (parsed with the GIL held: it reads Python objects).
scenario::RunSpec run_spec(const ScenarioSource& src, const py::object& seed, const py::object& robot,
                           const py::object& effects, const py::object& count) {
  YAML::Node root = src.is_text ? load_yaml_string(src.path_or_text, src.label) : load_yaml_file(src.path_or_text);
  if (!root.IsMap()) throw InputError(fmt::format("{}: expected a scenario (a map of sections)", src.label));
  const std::vector<std::string> names = apply_overrides(root, src, seed, robot, effects, count);
  scenario::RunSpec spec;
  if (names.empty()) {
    spec = src.is_text ? scenario::parse_run_spec(src.path_or_text, src.label, src.base_dir)
                       : scenario::load_run_spec(src.path_or_text);
  } else {
    YAML::Emitter em;
    em << root;
    spec = scenario::parse_run_spec(em.c_str(), fmt::format("{} (with {})", src.label, fmt::join(names, ", ")),
                                    src.base_dir);
  }
  if (spec.hardware)
    throw InputError(fmt::format("{}: hardware: gpm.run runs the twin; take samples through hardware with `gpm run "
                                 "--hardware`",
                                 src.label));
  return spec;
}

// gpm.run: the spec with the GIL held, then the run, its outputs and its summary without it.
py::object run(const py::object& scenario, const py::object& out_dir, const py::object& seed, const py::object& robot,
               const py::object& effects, const py::object& count, const py::object& base_dir,
               const py::object& progress) {
  const ScenarioSource src = scenario_source(scenario, base_dir);
  const scenario::RunSpec spec = run_spec(src, seed, robot, effects, count);
  std::optional<std::string> dir;
  if (!out_dir.is_none()) {
    dir = path_arg(out_dir, "out_dir");
    check_output_folder(*dir, {});  // not a file, not a hardware session's folder: refused before the run
  }
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw InputTypeError("progress: expected a callable taking the stage's name");
  scenario::Progress stages;  // the callable, with the GIL taken for it
  if (!progress.is_none())
    stages = [&progress](const std::string& stage) {
      py::gil_scoped_acquire locked;
      progress(stage);
    };
  std::string summary;
  {
    py::gil_scoped_release unlocked;
    const scenario::RunOutcome outcome = scenario::run_scenario(spec, src.label, stages);
    if (dir) scenario::write_run(outcome, *dir);
    summary = scenario::summary_json(outcome);
  }
  return py::module_::import("json").attr("loads")(summary);
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run", &run, py::arg("scenario"), py::arg("out_dir") = py::none(), py::kw_only(),
        py::arg("seed") = py::none(), py::arg("robot") = py::none(), py::arg("effects") = py::none(),
        py::arg("count") = py::none(), py::arg("base_dir") = py::none(), py::arg("progress") = py::none(),
        R"doc(
Runs a scenario as `gpm run` does: the twin takes the samples, the main
procedure calibrates, the controller takes the calibrated model, the twin
evaluates before and after, and the monitor watches `operation:` when the
scenario has one. Returns the summary as a dict, the content of summary.json
(verdict, robot_time_s, positioning_um, accuracy, parameters, model_test,
monitor). With out_dir, writes every output of `gpm run -o out_dir` there,
all or nothing.

scenario: a scenario file (str or os.PathLike), or scenario YAML text (a str
holding a newline; relative paths in it resolve against base_dir, default
the working folder).
Overrides (applied to the scenario before it is checked): seed (int >= 0),
robot (the controller's robot: a robot or calibration result file, or a dict
as an embedded robot map), effects (a preset name or a dict of the effects
section), count (sampling.count).
progress: a callable given each stage's name as it starts ("simulating the
twin", "calibrating", ...), as `gpm run` prints them.

The GIL is released while it runs: threads run robots in parallel. An
expectation that fails gives verdict "failed" (no exception). Raises
gpm.InputError for bad input, gpm.SimError when the physics diverges,
gpm.Error for a run that stops (the tracking watch, a calibration that
cannot use its samples).
)doc");

  m.def(
      "population_robot_scenario",
      [](const py::object& scenario_file, const py::object& seed_arg, const py::object& keep_effects_arg) {
        const bool keep_effects = flag_arg(keep_effects_arg, "keep_effects");
        const long long seed = whole_arg(seed_arg, "seed", limits::kSeed);
        return scenario::population_robot_scenario(path_arg(scenario_file, "scenario_file"),
                                                   static_cast<std::uint64_t>(seed), keep_effects);
      },
      py::arg("scenario_file"), py::arg("seed"), py::arg("keep_effects") = false,
      R"doc(
The scenario text of robot `seed` of a population (as `gpm study
population`): the file's YAML with that seed, effects randomized (unless
keep_effects), no expectations, the robot file's path made absolute.
gpm.run(text, base_dir=folder of scenario_file) runs that robot alone.
)doc");

  m.def(
      "scenario_seed",
      [](const py::object& scenario_file) {
        return scenario::load_run_spec(path_arg(scenario_file, "scenario_file")).sim.seed;
      },
      py::arg("scenario_file"), "The seed of a scenario file (its `seed:`, 1 when absent); checks the whole file.");
}

}  // namespace gpm::python
