// gpm design: excitation design (issue 10). Chooses the calibration poses that
// make the free parameters most accurate (calib/excitation/excitation.hpp) at
// the robot file's (nominal) geometry and writes them as a scenario sampling
// plan (calib/excitation/pose_list.hpp); with --compare, writes the table,
// CSV and figures comparing the paper's line, a circle, two random discs and
// the optimised set at equal poses and noise. --json prints one JSON document
// (the file's content and the bounds) instead of the text. Bad input exits 2
// with one line.
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/json_output.hpp"
#include "app/number_options.hpp"
#include "app/written_files.hpp"
#include "calib/excitation/excitation.hpp"
#include "calib/excitation/layouts.hpp"
#include "calib/excitation/pose_list.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/progress.hpp"
#include "models/robot_yaml.hpp"
#include "report/design_report.hpp"

namespace gpm::cli {
namespace {

namespace ex = calib::excitation;

struct DesignCliOptions {
  std::string model;
  int count = 50;
  double sigma = 1e-4;
  std::string fix = "xa1,ya1,xa2,ya2";
  std::string criterion = "worst";
  double grid_step = 5.0;
  double guard_mm = ex::Guard{}.reach_mm;
  bool compare = false;
  double radius = 80.0;
  double wide_radius = 150.0;
  std::uint64_t seed = 1;
  std::string out;
  bool json = false;
};

// Validated design options from the flags; throws InputError naming the flag.
ex::DesignOptions design_options(const DesignCliOptions& o) {
  return ex::checked_design_options(o.count, o.sigma, ~parse_param_list(o.fix, "--fix"), o.criterion, o.grid_step,
                                    o.guard_mm, true);
}

// Bounds as JSON: worst and mean (mm), the worst parameter, log det F, and
// each free parameter's bound (mm; offsets as rad x la_i); non-finite -> null.
Json bounds_json(const ex::Bounds& b) {
  Json per = Json::object();
  for (size_t k = 0; k < b.free_index.size(); ++k)
    per[std::string(param_name(b.free_index[k]))] = json_number(b.scaled[static_cast<Eigen::Index>(k)]);
  Json j;
  j["worst_mm"] = json_number(b.worst_mm);
  j["worst_param"] = b.worst_param >= 0 ? Json(std::string(param_name(b.worst_param))) : Json(nullptr);
  j["mean_mm"] = json_number(b.mean_mm);
  j["log_det"] = json_number(b.log_det);
  j["parameters_mm"] = per;
  return j;
}

// With the positioning criterion: the bound it reached, for the file's comment.
std::string positioning_note(const ex::Design& design) {
  if (!(design.positioning_bound_um > 0.0)) return "";
  return fmt::format("\npositioning bound over the disc round home: {:.3g} um RMS", design.positioning_bound_um);
}

std::string bound_note(const ex::Bounds& b) {
  return fmt::format("{:.4g} mm ({})", b.worst_mm, b.worst_param >= 0 ? std::string(param_name(b.worst_param)) : "-");
}

void run_design(const DesignCliOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  ex::DesignOptions d = design_options(o);
  const Robot robot = load_robot(o.model);
  // The design's stages on a terminal (models/progress.hpp).
  gpm::Progress progress = gpm::Progress::terminal("gpm design", "stages", ex::design_stages(d.criterion));
  if (progress.active()) d.progress = [&progress](int done, int) { progress.update(done); };
  const ex::Design design = ex::design_poses(robot, d);
  progress.finish();
  const std::string comment = fmt::format(
      "gpm design: {} poses, criterion {}, encoder noise {} rad, free {}\n"
      "designed at the geometry of {} (nominal: what is known before calibration)\n"
      "candidates: {} grid points of {} mm reachable with the robot's margins + guard {} mm\n"
      "Cramer-Rao bound here: worst {}, mean {:.4g} mm (offsets as rad x la_i){}\n"
      "use: gpm simulate THIS_FILE -o DIR, or paste the sampling block into a scenario",
      d.count, ex::criterion_name(d.criterion), d.sigma, format_param_list(d.free), o.model, design.candidates,
      d.grid_step_mm, d.guard.reach_mm, bound_note(design.bounds), design.bounds.mean_mm, positioning_note(design));
  const std::string text = ex::pose_list_yaml(design.poses, comment);
  write_output_file(o.out, text, {o.model});
  if (o.json) {
    // The pose list file's content, and under "design" what its comment says.
    Json doc = yaml_text_to_json(text, o.out);
    Json free = Json::array();
    for (int i = 0; i < kNumParams; ++i)
      if (d.free.test(static_cast<size_t>(i))) free.push_back(std::string(param_name(i)));
    Json info;
    info["model"] = o.model;
    info["poses"] = design.poses.size();
    info["criterion"] = ex::criterion_name(d.criterion);
    info["sigma_rad"] = d.sigma;
    info["free"] = free;
    info["candidates"] = design.candidates;
    info["grid_step_mm"] = d.grid_step_mm;
    info["guard_mm"] = d.guard.reach_mm;
    info["start_bounds"] = bounds_json(design.start_bounds);
    info["bounds"] = bounds_json(design.bounds);
    info["exchanges"] = design.exchanges;
    info["positioning_bound_um"] = d.criterion == ex::Criterion::kPositioning ? json_number(design.positioning_bound_um)
                                                                              : Json(nullptr);
    doc["design"] = info;
    print_json(doc);
    return;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("criterion        {}\n", ex::criterion_name(d.criterion));
  fmt::print("candidates       {} (grid {} mm)\n", design.candidates, d.grid_step_mm);
  fmt::print("greedy start     worst {}, mean {:.4g} mm, log det F {:.3f}\n", bound_note(design.start_bounds),
             design.start_bounds.mean_mm, design.start_bounds.log_det);
  fmt::print("optimised        worst {}, mean {:.4g} mm, log det F {:.3f}\n", bound_note(design.bounds),
             design.bounds.mean_mm, design.bounds.log_det);
  if (d.criterion == ex::Criterion::kPositioning)
    fmt::print("positioning      {:.3g} um RMS over the {:g} mm disc at best ({} readings per pose)\n",
               design.positioning_bound_um, d.positioning.radius_mm, d.positioning.samples_per_pose);
  fmt::print("exchanges        {} in {:.2f} s\n", design.exchanges, wall);
  fmt::print("wrote            {} ({} poses)\n", o.out, design.poses.size());
}

// The comparison's rows as the report library takes them (report/design_report.hpp).
report::DesignComparison comparison_data(const std::vector<ex::LayoutBounds>& rows, const ex::DesignOptions& d,
                                         const std::string& model) {
  report::DesignComparison c{model, d.count, d.sigma, d.free, ex::improvement_over_best_other(rows), {}};
  for (const auto& r : rows) {
    const ex::Bounds& b = r.bounds;
    c.layouts.push_back({r.name, r.description, r.poses, b.free_index, b.scaled, b.worst_mm, b.mean_mm, b.log_det,
                         b.worst_param});
  }
  return c;
}

void run_compare(const DesignCliOptions& o) {
  ex::ComparisonOptions c;
  c.design = design_options(o);
  if (!(o.radius > 0.0)) throw InputError(fmt::format("--radius: must be a positive number of mm, got {}", o.radius));
  if (!(o.wide_radius > 0.0))
    throw InputError(fmt::format("--wide-radius: must be a positive number of mm, got {}", o.wide_radius));
  c.radius = o.radius;
  c.wide_radius = o.wide_radius;
  c.seed = o.seed;
  const Robot robot = load_robot(o.model);
  const auto rows = ex::compare_layouts(robot, c);
  const report::DesignComparison data = comparison_data(rows, c.design, o.model);
  // All files or none (models/output_file.hpp), never over the model file.
  OutputFolder out(o.out, {o.model});
  report::design_comparison_report(data).stage(out, "design_comparison",
                                               "Excitation design: layouts at equal poses and noise");
  out.add("design_comparison.csv", report::design_comparison_csv(data));
  out.add("optimised_poses.yaml", ex::pose_list_yaml(rows.back().poses, "gpm design --compare: the optimised set"));
  out.commit();
  if (o.json) {
    // design_comparison.csv row by row (with each layout's poses), and the ratio.
    Json layouts = Json::array();
    for (const auto& r : rows) {
      Json poses = Json::array();
      for (const auto& p : r.poses) poses.push_back({p.x(), p.y()});
      Json l = bounds_json(r.bounds);
      l["layout"] = r.name;
      l["description"] = r.description;
      l["poses"] = poses;
      layouts.push_back(l);
    }
    Json doc;
    doc["layouts"] = layouts;
    doc["improvement_over_best_other"] = json_number(ex::improvement_over_best_other(rows));
    print_json(doc);
    return;
  }
  fmt::print("{:10} {:>14} {:>8} {:>14}\n", "layout", "worst (mm)", "param", "mean (mm)");
  for (const auto& r : rows)
    fmt::print("{:10} {:>14} {:>8} {:>14}\n", r.name, report::design_bound_text(r.bounds.worst_mm),
               r.bounds.worst_param >= 0 ? param_name(r.bounds.worst_param) : "-", report::design_bound_text(r.bounds.mean_mm));
  fmt::print("optimised is {:.1f}x better on the worst bound than the best other layout\n",
             ex::improvement_over_best_other(rows));
  print_written(o.out, 6);  // design_comparison.md, .html, .csv, .svg, design_layouts.svg, optimised_poses.yaml
}

}  // namespace

void add_design(CLI::App& app) {
  auto opt = std::make_shared<DesignCliOptions>();
  opt->model = default_model_path();
  auto* cmd = app.add_subcommand(
      "design", "Choose calibration poses (excitation design): a sampling plan YAML, or with --compare a layout comparison");
  cmd->add_option("--model", opt->model, "Robot file (YAML); the design uses its geometry (nominal)")->capture_default_str();
  cmd->add_option("--count", opt->count, "Number of poses")->capture_default_str();
  cmd->add_option("--sigma", opt->sigma, "Encoder noise, rad (scales the bounds; the poses do not depend on it)")
      ->capture_default_str();
  cmd->add_option("--fix", opt->fix, "Fixed (known) parameters, comma-separated")->capture_default_str();
  cmd->add_option("--criterion", opt->criterion,
                  "d (max log det Fisher), worst (min largest bound) or positioning (min positioning bound over the "
                  "80 mm disc, the encoders' error once per joint revolution estimated under the data sheet's prior; "
                  "depends on --sigma)")
      ->capture_default_str();
  cmd->add_option("--grid-step", opt->grid_step, "Candidate grid spacing, mm")->capture_default_str();
  cmd->add_option("--guard", opt->guard_mm, "Extra reach margin of the candidates, mm (also +0.02 on both singularity margins)")
      ->capture_default_str();
  cmd->add_flag("--compare", opt->compare, "Compare line, circle, discs and the optimised set; -o is a folder");
  cmd->add_option("--radius", opt->radius, "--compare: circle/disc radius and line half-length, mm")->capture_default_str();
  cmd->add_option("--wide-radius", opt->wide_radius, "--compare: radius of the wide disc, mm")->capture_default_str();
  cmd->add_option("--seed", opt->seed, "--compare: seed of the random discs")->capture_default_str()->transform(number_in(limits::kSeed));
  cmd->add_option("-o,--out", opt->out, "Pose list YAML (or folder with --compare)")->required();
  cmd->add_flag("--json", opt->json,
                "Print one JSON document on stdout instead of the text: the pose list file's content and the "
                "design's bounds (with --compare: the comparison table and each layout's poses)");
  cmd->callback([opt] {
    if (opt->compare) run_compare(*opt);
    else run_design(*opt);
  });
}

}  // namespace gpm::cli
