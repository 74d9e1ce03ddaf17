// gpm render SCENARIO.yaml -o VIDEO.mp4: simulates the scenario on the twin
// and renders its motion off-screen (render/): H.264 MP4 and PNG frames.
// A `gpm run` scenario (with calibration: or compensation:) is run as gpm
// run does and shown as a story: an opening card (robot, procedure, what
// is shown), the nominal controller on the test path, the sampling, the
// calibrated controller on the test path, and a closing card with the
// errors before and after, measured in that run.
// Options override the scenario's `render` section. Bad input (size, camera,
// frame, output path or suffix) exits 2 with one line before anything is
// simulated where possible; no partial file is left behind.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "calib/problem.hpp"
#include "models/errors.hpp"
#include "models/mjcf.hpp"
#include "models/output_file.hpp"
#include "models/progress.hpp"
#include "models/yaml_util.hpp"
#include "render/overlay_painter.hpp"
#include "report/table_cell.hpp"
#include "render/render_options.hpp"
#include "render/scene_renderer.hpp"
#include "render/video_job.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"
#include "sim/simulate.hpp"

namespace gpm::cli {
namespace {

struct RenderCliOptions {
  std::string scenario;
  std::string beside;
  std::string out;
  double fps = 0.0;
  double speed = 0.0;
  std::string size;
  std::string camera;
  std::string quality;
  std::vector<std::string> frame_png;
  bool simulation_only = false;
};

sim::SimulationResult run(const sim::Scenario& s, const std::string& file) {
  try {
    Progress progress = Progress::terminal("gpm render: simulating", "simulated s");  // on a terminal only
    return sim::run_simulation(s, nullptr, &progress);
  } catch (const sim::SimError& e) {
    throw InputError(fmt::format("{}: {}", file, e.what()));
  }
}

// A scenario for `gpm run`: it calibrates or compensates.
bool is_run_scenario(const std::string& file) {
  const YAML::Node root = load_yaml_file(file);  // the same bounded, checked reading as every input
  return root.IsMap() && (root["calibration"] || root["compensation"]);
}

// The story of a gpm run scenario (run as gpm run runs it, always on the twin):
// the nominal controller on the test path, the sampling, the calibrated
// controller on the test path (the parts that exist).
struct Story {
  scenario::RunOutcome outcome;
  std::vector<std::vector<render::RunView>> parts;
  render::Cards cards;
  std::vector<render::RunView> sampling;  // the sampling alone (--simulation-only), empty when none
};

// A caption on one line ("1/3 nominal model test path").
std::string one_line(std::string caption) {
  std::replace(caption.begin(), caption.end(), '\n', ' ');
  return caption;
}

// How the samples were taken: "9100 readings on the fly through 40 designed
// poses (9.1 s of robot motion)".
std::string sampling_text(const scenario::RunOutcome& o) {
  const std::optional<sim::SamplingPlan>& plan = o.spec.sim.sampling;
  const size_t poses = plan ? std::max<size_t>(static_cast<size_t>(std::max(0, plan->count)), plan->poses.size()) : 0;
  if (o.in_motion && poses > 0)
    return fmt::format("{} readings taken on the fly along a path through {} designed poses ({:.1f} s of robot motion)",
                       o.sim.samples.size(), poses, o.sim.sampling_s);
  return fmt::format("{} samples {} ({:.1f} s of robot motion)", o.sim.samples.size(),
                     o.in_motion ? "on the fly" : "at standstill", o.sim.sampling_s);
}

// The opening card: the robot, the procedure (the scenario's description and
// its sampling and calibration) and the parts shown.
render::Card opening_card(const Story& story, const std::string& file) {
  const scenario::RunOutcome& o = story.outcome;
  const YAML::Node root = load_yaml_file(file);
  const std::string description =
      root["description"] && root["description"].IsScalar() ? root["description"].as<std::string>() : o.spec.sim.name;
  render::Card c;
  c.title = fmt::format("{}: calibration on its digital twin", o.nominal.name);
  c.rows.push_back({"robot", fmt::format("{}, a 3-RRR planar parallel robot, simulated in MuJoCo", o.nominal.name)});
  c.rows.push_back({"procedure", description});
  if (!o.sim.samples.empty())
    c.rows.push_back({"", sampling_text(o) + ","});
  const calib::Method m = o.spec.calibration.method;
  std::string cost(calib::cost_name(o.spec.calibration.cost));
  std::transform(cost.begin(), cost.end(), cost.begin(), [](unsigned char ch) { return std::toupper(ch); });
  c.rows.push_back({"", fmt::format("then the {} calibration ({})", cost,
                                    m == calib::Method::kLM ? "Levenberg-Marquardt" : calib::method_name(m))});
  c.rows.push_back({""});
  for (size_t i = 0; i < story.parts.size(); ++i)
    c.rows.push_back({i == 0 ? "shown" : "", one_line(story.parts[i].front().label)});
  if (o.before && o.after) c.rows.push_back({"", "then the errors before and after, measured in this run"});
  c.rows.push_back({"", "cyan arrow: the tracking error, magnified as the panel states"});
  c.seconds = 5.0;
  return c;
}

// The closing card: the nominal and calibrated models' static positioning and
// tracking errors, as this run measured them, and the robot time of the
// sampling (none without both).
std::optional<render::Card> closing_card(const scenario::RunOutcome& o) {
  if (!o.before || !o.after) return std::nullopt;
  const auto d = [](double um) { return render::distance_text(um / 1000.0); };
  render::Card c;
  c.title = fmt::format("{}: before and after calibration", o.nominal.name);
  c.rows.push_back({"error (RMS)", "nominal", "calibrated"});
  c.rows.push_back({fmt::format("at {} poses", o.before->static_error_um.size()), d(o.before->static_rms_um),
                    d(o.after->static_rms_um)});
  c.rows.push_back({"on the path", d(o.before->path_rms_um), d(o.after->path_rms_um)});
  if (!o.sim.samples.empty())  // how long the calibration keeps the robot from its work: its sampling
    c.rows.push_back({"time off work", fmt::format("{:.1f} s, {}", o.sim.sampling_s, o.in_motion ? "on the fly" : "at rest")});
  c.rows.push_back({""});
  if (o.refused) c.rows.push_back({fmt::format("calibration refused: {}", *o.refused)});
  else if (o.after->static_rms_um > 0)
    c.rows.push_back({fmt::format("Standing still, the error is {}x smaller.",
                                  report::ratio_text(o.before->static_rms_um / o.after->static_rms_um))});
  c.rows.push_back({"Measured on the twin in this run."});
  c.seconds = 5.0;
  c.large = true;
  return c;
}

std::unique_ptr<Story> run_story(const std::string& file) {
  scenario::RunSpec spec = scenario::load_run_spec(file);
  spec.hardware.reset();  // a video shows the twin
  const bool tty = ::isatty(STDERR_FILENO);
  scenario::Progress stages;
  if (tty) stages = [](const std::string& stage) { std::fprintf(stderr, "gpm render: %s ...\n", stage.c_str()); };
  auto story = std::make_unique<Story>();
  try {
    story->outcome = scenario::run_scenario(spec, file, stages);
  } catch (const sim::SimError& e) {
    throw InputError(fmt::format("{}: {}", file, e.what()));
  }
  const scenario::RunOutcome& o = story->outcome;
  const auto view = [&o](const std::string& caption, const sim::TrajectoryLog& log) {
    return std::vector<render::RunView>{render::RunView{caption, o.sim.actual, o.sim.model_xml, &log}};
  };
  const bool before = o.before && !o.before->path_log.rows.empty();
  const bool after = o.after && !o.after->path_log.rows.empty();
  const int n = (before ? 1 : 0) + (o.sim.log.rows.empty() ? 0 : 1) + (after ? 1 : 0);
  int k = 0;
  if (before) story->parts.push_back(view(fmt::format("{}/{} nominal model\ntest path", ++k, n), o.before->path_log));
  if (!o.sim.log.rows.empty()) {
    story->parts.push_back(view(fmt::format("{}/{} sampling for\nthe calibration", ++k, n), o.sim.log));
    story->sampling = view("sampling for\nthe calibration", o.sim.log);
  }
  if (after) story->parts.push_back(view(fmt::format("{}/{} calibrated model\ntest path", ++k, n), o.after->path_log));
  if (story->parts.empty()) throw InputError(fmt::format("{}: the run has no motion to show", file));
  story->cards.opening = opening_card(*story, file);
  story->cards.closing = closing_card(o);
  return story;
}

// The render options: the scenario's `render` section, overridden by the flags given.
render::RenderOptions render_options(const RenderCliOptions& opt, bool fps_given, bool speed_given) {
  render::RenderOptions o = render::render_options_from_file(opt.scenario);
  if (!opt.size.empty()) render::parse_size(opt.size, "--size", o.width, o.height);
  if (fps_given) {  // given: 0 is refused like any other impossible rate
    if (!(opt.fps > 0 && opt.fps <= 240)) throw InputError(fmt::format("--fps: must be in (0, 240], got {}", opt.fps));
    o.fps = opt.fps;
  }
  if (speed_given) {
    if (!(opt.speed > 0)) throw InputError(fmt::format("--speed: must be positive, got {}", opt.speed));
    o.speed = opt.speed;
  }
  if (!opt.camera.empty()) o.camera = opt.camera;
  if (!opt.quality.empty()) o.quality = render::parse_quality(opt.quality, "--quality");
  return o;
}

// Loads every scenario and checks that its model renders with the options' camera.
std::vector<sim::Scenario> load_scenarios(const RenderCliOptions& opt, const render::RenderOptions& o,
                                          const std::vector<std::string>& files) {
  std::vector<sim::Scenario> scenarios;
  for (const std::string& f : files) {
    scenarios.push_back(sim::load_scenario(f));
    const Robot actual = sim::make_actual(scenarios.back());
    render::check_render_setup(mjcf_from_robot(actual, scenarios.back().twin.mjcf), o,
                               opt.camera.empty() ? f + ": render.camera" : "--camera");
  }
  return scenarios;
}

// Refuses an output that is an input (models/output_file.hpp) or whose suffix is not what is written.
void check_outputs(const RenderCliOptions& opt, const std::vector<render::FrameRequest>& pngs,
                   const std::vector<std::string>& files) {
  if (!opt.out.empty()) check_output_file(opt.out, files);
  for (const render::FrameRequest& p : pngs) check_output_file(p.path, files);
  // The suffix says the format: only what is written is accepted (render/video_job.hpp).
  if (!opt.out.empty()) render::check_output_suffix(opt.out, ".mp4", "-o");
  for (const render::FrameRequest& p : pngs) render::check_output_suffix(p.path, ".png", "--frame-png");
}

// The simulated runs shown side by side, one part (the results own the logs the views point at).
std::vector<std::vector<render::RunView>> simulation_parts(const std::vector<sim::Scenario>& scenarios,
                                                           const std::vector<std::string>& files,
                                                           std::vector<sim::SimulationResult>& results) {
  for (size_t i = 0; i < scenarios.size(); ++i) results.push_back(run(scenarios[i], files[i]));
  std::vector<render::RunView> views;
  for (size_t i = 0; i < results.size(); ++i) views.push_back(render::run_view(results[i], scenarios[i].name));
  return {views};
}

// Prints what was rendered and written.
void print_render_summary(const RenderCliOptions& opt, const render::RenderOptions& o,
                          const std::vector<std::string>& files, const render::VideoSummary& v, bool story,
                          const std::vector<std::vector<render::RunView>>& parts,
                          const std::vector<render::FrameRequest>& pngs, const render::Cards& cards) {
  fmt::print("scenario         {}\n", fmt::join(files, " | "));
  fmt::print("frames           {} at {} fps, {}x{}, camera {}, quality {}\n", v.frames, o.fps, v.width, v.height,
             o.camera, render::quality_name(o.quality));
  if (story) {
    for (const render::Segment& g : v.segments) {
      if (g.kind == render::Segment::Kind::kPart)
        fmt::print("part             {} from frame {}\n", one_line(parts[static_cast<size_t>(g.part)].front().label),
                   g.first);
      else
        fmt::print("card             {}{} from frame {}\n",
                   g.kind == render::Segment::Kind::kOpening ? "opening" : "closing",
                   g.pages > 1 ? fmt::format(" in {} pages", g.pages) : "", g.first);
    }
  }
  fmt::print("rendered         {:.1f} frames/s ({:.2f} s wall, {})\n", v.frames_per_s, v.wall_s, v.gl_renderer);
  if (cards.closing) {
    for (const auto& row : cards.closing->rows)
      if (row.size() == 3 && row[1] != "nominal")
        fmt::print("error RMS        {}: {} nominal, {} calibrated\n", row[0], row[1], row[2]);
  }
  if (!opt.out.empty()) fmt::print("wrote            {} ({})\n", opt.out, v.codec);
  for (const render::FrameRequest& p : pngs) fmt::print("wrote            {} (frame {})\n", p.path, p.frame);
}

// gpm render: checks everything, simulates (or runs the story), renders and prints a summary.
void run_render(const RenderCliOptions& opt, bool fps_given, bool speed_given) {
  if (opt.out.empty() && opt.frame_png.empty()) throw InputError("gpm render: give -o VIDEO.mp4 and/or --frame-png N:FILE");
  const render::RenderOptions o = render_options(opt, fps_given, speed_given);
  std::vector<render::FrameRequest> pngs;
  for (const std::string& f : opt.frame_png) pngs.push_back(render::parse_frame_request(f, "--frame-png"));
  std::vector<std::string> files = {opt.scenario};
  if (!opt.beside.empty()) files.push_back(opt.beside);
  const std::vector<sim::Scenario> scenarios = load_scenarios(opt, o, files);
  check_outputs(opt, pngs, files);

  const bool run_file = opt.beside.empty() && is_run_scenario(opt.scenario);
  const bool story = run_file && !opt.simulation_only;
  std::unique_ptr<Story> ran;
  std::vector<sim::SimulationResult> results;
  std::vector<std::vector<render::RunView>> parts;
  render::Cards cards;
  if (story) {
    render::check_card_size(o.width, o.height, opt.size.empty() ? opt.scenario + ": render.size" : "--size");
    ran = run_story(opt.scenario);
    parts = ran->parts;
    cards = ran->cards;
  } else if (run_file) {  // --simulation-only: the story's sampling alone, from the same run (the one loop)
    ran = run_story(opt.scenario);
    if (ran->sampling.empty()) throw InputError(fmt::format("{}: the run samples nothing to show", opt.scenario));
    parts = {ran->sampling};
  } else {
    parts = simulation_parts(scenarios, files, results);
  }
  // A progress line on a terminal (frames, fps, ETA); PNG-only renders are short.
  int total = 0;
  for (const render::Segment& g : render::video_segments(parts, o, cards, render::card_pages(parts, o, cards)))
    total += g.count;
  Progress progress = Progress::terminal("gpm render", "frames", opt.out.empty() ? 0 : total);
  render::VideoJobOptions job;
  job.progress = opt.out.empty() ? nullptr : &progress;
  const render::VideoSummary v = render::render_parts(parts, o, opt.out, pngs, job, cards);
  print_render_summary(opt, o, files, v, story, parts, pngs, cards);
}

}  // namespace

void add_render(CLI::App& app) {
  auto opt = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand("render", kRenderDescription);
  cmd->add_option("scenario", opt->scenario, "Scenario file (YAML, see gpm help schema), or a scenario of the library by name (gpm help scenarios)")
      ->required();
  cmd->add_option("-o,--out", opt->out, "Output video (H.264 MP4; the name must end in .mp4)");
  CLI::Option* fps = cmd->add_option("--fps", opt->fps, "Video frames per second (default 30)");
  cmd->add_option("--size", opt->size, "Frame size WxH in pixels, even (default 640x480)");
  cmd->add_option("--camera", opt->camera, "Camera: top (default), oblique, or a camera of the model");
  cmd->add_option("--quality", opt->quality, "fast (default: no multisampling, no shadows) or high (4x MSAA, shadows)");
  CLI::Option* speed = cmd->add_option("--speed", opt->speed, "Simulated seconds per video second (default 1)");
  cmd->add_option("--frame-png", opt->frame_png, "Save frame N (0-based) as a PNG: N:FILE (repeatable)");
  cmd->add_option("--beside", opt->beside, "A second scenario shown side by side (e.g. the calibrated controller)");
  cmd->add_flag("--simulation-only", opt->simulation_only,
                "For a gpm run scenario: only its sampling (as the story shows it), not the story of the run");
  cmd->callback([opt, fps, speed] {
    opt->scenario = resolve_scenario(opt->scenario);  // a file, or a library name (gpm render main)
    if (!opt->beside.empty()) opt->beside = resolve_scenario(opt->beside);
    run_render(*opt, fps->count() > 0, speed->count() > 0);
  });
}

}  // namespace gpm::cli
