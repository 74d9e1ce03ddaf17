#include "run/expectations.hpp"

#include <cmath>

#include <fmt/format.h>

#include "run/runner.hpp"

namespace gpm::scenario {
namespace {

void check(std::vector<Check>& out, const std::string& name, bool ok, const std::string& detail) {
  out.push_back({name, ok, detail});
}

// The check `name`: a parameter's error over its scale (what `what` calls
// it) at most limit; a scale that is not known fails.
void check_ratio(std::vector<Check>& out, const std::string& name, const char* what, double err, double scale,
                 double limit) {
  const double ratio = err / scale;
  check(out, name, std::isfinite(ratio) && ratio <= limit,
        fmt::format("|error| / {} = {:.3g} / {:.3g} = {:.3g} (limit {:.3g})", what, err, scale, ratio, limit));
}


// The per-parameter checks: each free parameter's error against its tolerance, its CRB and its stated 1-sigma.
void check_parameters(std::vector<Check>& out, const RunOutcome& o, const calib::Result& r) {
  const Expectations& e = o.spec.expect;
  const Geometry& truth = o.sim.actual.geometry;
  for (int i = 0; i < kNumParams; ++i) {
    if (!r.free.test(static_cast<size_t>(i))) continue;
    const double err = std::abs(r.geometry[i] - truth[i]);
    std::optional<double> tol = e.param[static_cast<size_t>(i)];
    if (!tol) tol = is_offset(i) ? e.offset_rad : is_length(i) ? e.link_mm : e.base_mm;
    if (tol) {
      check(out, fmt::format("error.{}", param_name(i)), err <= *tol,
            fmt::format("|{:.6g} - {:.6g}| = {:.3g} (limit {:.3g})", r.geometry[i], truth[i], err, *tol));
    }
    if (e.crb_ratio_max) {
      check_ratio(out, fmt::format("crb_ratio.{}", param_name(i)), "CRB", err, o.crb[static_cast<size_t>(i)],
                  *e.crb_ratio_max);
    }
    if (e.sigma_ratio_max) {
      check_ratio(out, fmt::format("sigma_ratio.{}", param_name(i)), "stated 1-sigma", err,
                  r.sigma[static_cast<size_t>(i)], *e.sigma_ratio_max);
    }
  }
}

// The fit's checks: final cost, kmrmse, a note.
void check_fit(std::vector<Check>& out, const Expectations& e, const calib::Result& r) {
  if (e.cost_max) {
    check(out, "cost", r.final_cost <= *e.cost_max, fmt::format("J = {:.4g} (limit {:.3g})", r.final_cost, *e.cost_max));
  }
  if (e.kmrmse_mm_max) {
    const bool ok = r.kmrmse_mm && *r.kmrmse_mm <= *e.kmrmse_mm_max;
    check(out, "kmrmse", ok,
          r.kmrmse_mm ? fmt::format("kmrmse = {:.4g} mm (limit {:.3g})", *r.kmrmse_mm, *e.kmrmse_mm_max)
                      : "no kmrmse (samples without x,y)");
  }
  for (const std::string& text : e.note_contains) {
    bool ok = false;
    for (const auto& n : r.notes) ok = ok || n.find(text) != std::string::npos;
    check(out, "note_contains", ok, ok ? "found" : fmt::format("no note contains '{}'", text));
  }
}

// The positioning error's check (what a user gets of the calibrated model).
void check_positioning(std::vector<Check>& out, const RunOutcome& o) {
  const Expectations& e = o.spec.expect;
  if (!e.positioning_rms_um_max) return;
  check(out, "positioning_rms_um", o.positioning && o.positioning->rms_um <= *e.positioning_rms_um_max,
        o.positioning ? fmt::format("{:.3f} um RMS over the workspace disc (limit {:.3g})", o.positioning->rms_um,
                                    *e.positioning_rms_um_max)
                      : "no positioning error (no calibration, or measured on hardware)");
}

// The model test's check (expected to pass or to fail).
void check_model_test(std::vector<Check>& out, const RunOutcome& o) {
  const Expectations& e = o.spec.expect;
  if (e.model_test_passes) {
    const bool ok = o.model_test && o.model_test->passed == *e.model_test_passes;
    check(out, "model_test", ok,
          o.model_test ? fmt::format("chi2 {:.4g} for {:.0f} degrees of freedom, p = {:.3g} ({}; expected to {})",
                                     o.model_test->chi2, o.model_test->dof, o.model_test->p_value,
                                     o.model_test->passed ? "passes" : "fails",
                                     *e.model_test_passes ? "pass" : "fail")
                       : "no model test (ML cost with a known encoder sigma only)");
  }
}

// The compensation's checks: the floor ratio, the static and path RMS, the improvement.
void check_compensation(std::vector<Check>& out, const RunOutcome& o) {
  const Expectations& e = o.spec.expect;
  if (e.floor_ratio_max) {
    const bool ok = o.after && o.floor && o.floor->static_rms_um > 0.0 &&
                    o.after->static_rms_um <= *e.floor_ratio_max * o.floor->static_rms_um;
    check(out, "floor_ratio", ok,
          o.after && o.floor ? fmt::format("static RMS {:.3f} um calibrated, {:.3f} um with the actual parameters: "
                                           "x{:.3g} (limit x{:.3g})",
                                           o.after->static_rms_um, o.floor->static_rms_um,
                                           o.after->static_rms_um / o.floor->static_rms_um, *e.floor_ratio_max)
                             : "no compensation run with the actual parameters");
  }
  if (e.static_rms_um_max || e.path_rms_um_max || e.improvement_min) {
    if (!o.after || !o.before) {
      check(out, "compensation", false, "no compensation run (outputs.compensation is off)");
      return;
    }
    if (e.static_rms_um_max) {
      check(out, "static_rms_um", o.after->static_rms_um <= *e.static_rms_um_max,
            fmt::format("{:.3f} um after calibration (limit {:.3g})", o.after->static_rms_um, *e.static_rms_um_max));
    }
    if (e.path_rms_um_max) {
      check(out, "path_rms_um", o.after->path_rms_um <= *e.path_rms_um_max,
            fmt::format("{:.3f} um after calibration (limit {:.3g})", o.after->path_rms_um, *e.path_rms_um_max));
    }
    if (e.improvement_min) {
      const double ratio = o.before->static_rms_um / o.after->static_rms_um;
      check(out, "improvement", ratio >= *e.improvement_min,
            fmt::format("static RMS {:.3f} -> {:.3f} um, x{:.3g} (at least x{:.3g})", o.before->static_rms_um,
                        o.after->static_rms_um, ratio, *e.improvement_min));
    }
  }
}

}  // namespace

std::vector<Check> evaluate_expectations(const RunOutcome& o) {
  std::vector<Check> out;
  const Expectations& e = o.spec.expect;
  if (e.refused_contains) {
    const bool ok = o.refused && o.refused->find(*e.refused_contains) != std::string::npos;
    check(out, "refused_contains", ok,
          o.refused ? fmt::format("refused: {}", *o.refused) : "the calibration was not refused");
  }
  if (!o.calibration) {
    // Nothing else can be checked; any other expectation fails honestly.
    const bool others = e.converged || e.base_mm || e.link_mm || e.offset_rad || e.cost_max ||
                        e.kmrmse_mm_max || e.crb_ratio_max || e.sigma_ratio_max || e.static_rms_um_max ||
                        e.path_rms_um_max || e.improvement_min;
    if (others) check(out, "calibration", false, "no calibration result to check");
    return out;
  }
  const calib::Result& r = *o.calibration;
  // A run whose solver did not converge fails unless the scenario expects that.
  const bool want_converged = e.converged.value_or(true);
  if (e.converged || !r.converged) {
    check(out, "converged", r.converged == want_converged, fmt::format("converged = {}", r.converged));
  }
  check_parameters(out, o, r);
  check_fit(out, e, r);
  if (e.robot_time_s_max) {
    check(out, "robot_time_s", o.sim.sampling_s <= *e.robot_time_s_max,
          fmt::format("{:.2f} s of robot time sampling (limit {:.3g})", o.sim.sampling_s, *e.robot_time_s_max));
  }
  check_model_test(out, o);
  check_positioning(out, o);
  check_compensation(out, o);
  return out;
}

}  // namespace gpm::scenario
