// Calibration from readings taken in motion (calib/motion_correction.hpp).
#include "calib/motion_correction.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "calib/chi_square.hpp"
#include "calib/identifiability.hpp"
#include "calib/model_test.hpp"
#include "calib/parameterization.hpp"
#include "calib/passive_tension.hpp"
#include "calib/reading_model.hpp"
#include "calib/residuals.hpp"
#include "calib/play_crossing.hpp"
#include "calib/sample_weights.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

// ML residual of one reading triple at solver vector x.
double ml_residual(const ParamVector& x, const Eigen::Vector3d& theta) {
  double r = std::numeric_limits<double>::quiet_NaN();
  MlResidual{theta}(x.data(), &r);
  return r;
}

// The nuisance columns (nuisance_columns): where each value's slots start.
constexpr int kSkew = 0;          // s2 s3
constexpr int kCompliance = 2;    // c1 c2 c3
constexpr int kFriction = 5;      // c1 F1, c2 F2, c3 F3
constexpr int kClearance = 8;     // d1 d2 d3
constexpr int kBefore = 11;       // h1 h2 h3
constexpr int kFirstCyclic = 14;  // a1 a2 a3 b1 b2 b3 under the data sheet's prior
constexpr int kBacklash = 20;     // beta1 beta2 beta3
constexpr int kHarmonic = 23;     // the orders (joint, motor, 2 x motor, cogging), each a1 a2 a3 b1 b2 b3
constexpr int kHysteresis = kHarmonic + 6 * kHarmonicOrders;  // eta1 eta2 eta3
constexpr std::size_t kNuisance = kHysteresis + 3;
// Relative cost decrease at which the passes' LM fits stop (the last fit of
// fit_in_motion polishes to LmOptions::function_tolerance).
constexpr double kPassFunctionTolerance = 1e-10;

// The change of the drive torques from the sample before to each one:
// model.torque_between(j) - tau(j) where recorded (one per sample), else
// tau(j-1) - tau(j) (consecutive samples on the fly; 0 for the first); an
// empty vector without model.torque_before.
std::vector<Eigen::Vector3d> torques_before(const MotionModel& model, const std::vector<Eigen::Vector3d>& tau) {
  std::vector<Eigen::Vector3d> nb;
  if (!(model.compliance && model.torque_before)) return nb;
  if (!model.torque_between.empty()) {
    if (model.torque_between.size() != tau.size())
      throw InputError(fmt::format("calibration in motion: {} torques but {} torques between samples", tau.size(),
                                   model.torque_between.size()));
    for (std::size_t j = 0; j < tau.size(); ++j) nb.push_back(model.torque_between[j] - tau[j]);
    return nb;
  }
  for (std::size_t j = 0; j < tau.size(); ++j) nb.push_back(tau[j > 0 ? j - 1 : 0] - tau[j]);
  return nb;
}

// Share of the samples each sign of a passive link's force must hold for its play to be estimated.
constexpr double kMinSignShare = 0.02;

// Columns of the nuisance Jacobian that model estimates (0..4 = s2 s3 c1 c2 c3, 5..7 = c1 F1, c2 F2, c3 F3,
// 8..10 = d1 d2 d3, 11..13 = h1 h2 h3, 14..16 = a1 a2 a3, 17..19 = b1 b2 b3).
std::vector<int> nuisance_columns(const MotionModel& m) {
  std::vector<int> cols;
  const auto add = [&](int first, int count) {  // (a loop: GCC 12 warns wrongly on insert of a list)
    for (int c = first; c < first + count; ++c) cols.push_back(c);
  };
  if (m.skew) add(0, 2);
  if (m.compliance) add(2, 3);
  if (m.compliance && m.friction) add(5, 3);
  if (m.clearance) add(8, 3);
  if (m.compliance && m.torque_before) add(11, 3);
  if (m.cyclic_prior_rad > 0.0 && m.estimate_cyclic) add(kFirstCyclic, 6);
  for (int i = 0; i < 3; ++i)
    if (m.backlash[static_cast<std::size_t>(i)]) cols.push_back(kBacklash + i);
  const std::array<const std::array<bool, 3>*, kHarmonicOrders> orders{&m.joint_harmonic, &m.motor_harmonic1,
                                                                       &m.motor_harmonic2, &m.cogging};
  for (int o = 0; o < kHarmonicOrders; ++o)
    for (int i = 0; i < 3; ++i)
      if ((*orders[static_cast<std::size_t>(o)])[static_cast<std::size_t>(i)])
        cols.push_back(kHarmonic + 6 * o + i), cols.push_back(kHarmonic + 6 * o + 3 + i);
  for (int i = 0; i < 3; ++i)
    if (m.hysteresis[static_cast<std::size_t>(i)]) cols.push_back(kHysteresis + i);
  return cols;
}

// True when model carries the cyclic error unestimated in the covariance.
bool considers_cyclic(const MotionModel& m) { return m.cyclic_prior_rad > 0.0 && !m.estimate_cyclic; }

// The covariance C (of the estimated columns of J) of an estimator that
// leaves out the columns Jc whose coefficients are N(0, prior^2): C plus
// prior^2 G G' with G = (J' J)^-1 J' Jc, the estimate's response to them
// (a "consider" covariance). A is (J' J)^-1.
void add_considered(const Eigen::MatrixXd& A, const Eigen::MatrixXd& J, const Eigen::MatrixXd& Jc, double prior,
                    Eigen::MatrixXd& C) {
  const Eigen::MatrixXd G = A * (J.topRows(Jc.rows()).transpose() * Jc);
  C += prior * prior * G * G.transpose();
}

// What the clearance needs of one sample (calib/passive_tension.hpp): the
// axial force T_i of each passive link (N) and the reading change per mm of
// its length, 1 / (la_i sin(theta_b_i - theta_a_i)) (rad/mm).
struct PassiveForces {
  Eigen::Vector3d tension, per_mm;
};

// PassiveForces of each sample at geometry g with readings theta_m (rad) and
// the torques tau_t transmitted to the active links; nullopt where the
// forward kinematics fails.
std::vector<std::optional<PassiveForces>> passive_forces(const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m,
                                                         const std::vector<Eigen::Vector3d>& tau_t) {
  std::vector<std::optional<PassiveForces>> out(theta_m.size());
  for (std::size_t j = 0; j < theta_m.size(); ++j) {
    Eigen::Vector3d theta_a;
    for (int i = 0; i < 3; ++i) theta_a[i] = theta_m[j][i] + g.dth_(i);
    const std::optional<ForwardResult> fk = forward_kinematics(g, theta_a);
    if (!fk) continue;
    PassiveForces f;
    for (int i = 0; i < 3; ++i) {
      f.tension[i] = passive_link_tension(g, i, theta_a[i], fk->theta_b[i], tau_t[j][i]);
      f.per_mm[i] = reading_per_passive_length(g, i, theta_a[i], fk->theta_b[i]);
    }
    out[j] = f;
  }
  return out;
}

// Clearance regressors (calib/motion_correction.hpp): per sample and chain,
// sign(T_i) / (la_i sin(theta_b_i - theta_a_i)) (rad/mm), 0 where |T_i| is
// below tension_min_N (its sign uncertain) or the sample's forces are unknown.
std::vector<Eigen::Vector3d> clearance_regressors(const std::vector<std::optional<PassiveForces>>& forces,
                                                  double tension_min_N) {
  std::vector<Eigen::Vector3d> out(forces.size(), Eigen::Vector3d::Zero());
  for (std::size_t j = 0; j < forces.size(); ++j) {
    if (!forces[j]) continue;
    for (int i = 0; i < 3; ++i) {
      const double tension = forces[j]->tension[i];
      if (!(std::abs(tension) >= tension_min_N)) continue;
      out[j][i] = (tension > 0.0 ? 1.0 : -1.0) * forces[j]->per_mm[i];
    }
  }
  return out;
}

// sign_flip_variance per sample and chain of the signs clearance_regressors
// uses (|T_i| >= tension_min_N), each force known within
// model.tension_sigma_N (0: certain) and, where its joint may be at rest
// (speeds omega below the stick speed), within the friction F_i it may hold
// as well: a torque uniform on +-F_i moves T_i by it over la_i sin(theta_b - theta_a).
std::vector<Eigen::Vector3d> flip_variances(const std::vector<std::optional<PassiveForces>>& forces,
                                            double tension_min_N, const MotionModel& model,
                                            const std::vector<Eigen::Vector3d>& omega) {
  std::vector<Eigen::Vector3d> out(forces.size(), Eigen::Vector3d::Zero());
  if (!(model.tension_sigma_N > 0.0)) return out;
  for (std::size_t j = 0; j < forces.size(); ++j)
    for (int i = 0; forces[j] && i < 3; ++i) {
      if (!(std::abs(forces[j]->tension[i]) >= tension_min_N)) continue;
      const double per_m = 1e3 * forces[j]->per_mm[i];  // 1 / (la_i sin(theta_b - theta_a)), la_i in m
      const double rest = rest_twist_variance(omega[j][i], model.load.coulomb_Nm[static_cast<std::size_t>(i)] * per_m,
                                              model.stick_speed_rad_s);
      const double sigma = std::sqrt(model.tension_sigma_N * model.tension_sigma_N + rest);
      out[j][i] = sign_flip_variance(forces[j]->tension[i], sigma, forces[j]->per_mm[i]);
    }
  return out;
}

// The force threshold calibrate_in_motion uses (MotionModel::min_kept_share):
// model.tension_min_N, or the weakest force of the min_kept_share strongest
// samples when fewer samples clear it; from the samples' forces (none: the
// model's threshold).
double effective_tension_min(const MotionModel& model, const std::vector<std::optional<PassiveForces>>& forces) {
  if (!model.clearance || !model.drop_uncertain || forces.empty()) return model.tension_min_N;
  std::vector<double> weakest(forces.size(), 0.0);  // min_i |T_i| per sample
  for (std::size_t j = 0; j < forces.size(); ++j)
    if (forces[j]) {
      double w = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 3; ++i) w = std::min(w, std::abs(forces[j]->tension[i]));
      weakest[j] = w;
    }
  const auto want = static_cast<std::size_t>(std::ceil(std::clamp(model.min_kept_share, 0.0, 1.0) * static_cast<double>(weakest.size())));
  const auto above = static_cast<std::size_t>(std::count_if(weakest.begin(), weakest.end(), [&](double w) { return w >= model.tension_min_N; }));
  if (want == 0 || above >= want) return model.tension_min_N;
  std::nth_element(weakest.begin(), weakest.begin() + static_cast<std::ptrdiff_t>(want - 1), weakest.end(), std::greater<>());
  return weakest[want - 1];
}

// Reading sensitivities u_k = dr / dtheta_m_k of the ML residual of sample
// j: the residual depends on theta_m_k and dth_k only through their sum
// theta_a_k (eq. 35), so u_k is the dth_k column of its Jacobian J_all (ml_jacobian).
Eigen::Vector3d reading_sensitivity(const Eigen::MatrixXd& J_all, std::size_t j) {
  const auto row = static_cast<Eigen::Index>(j);
  return {J_all(row, dth(0)), J_all(row, dth(1)), J_all(row, dth(2))};
}

// What one sample offers the nuisance columns besides its reading
// sensitivities: speed, torque, friction and clearance regressors, the change
// of torque from the sample before (nb), the raw readings (for the cyclic
// errors) and the sign of each mesh's torque (0 uncertain; calib/motion_correction.hpp).
// sin and cos of one raw reading and of its harmonic angles
// (harmonic_angle, orders 0..3): sin r, cos r, then sin a_o, cos a_o.
using Wave = std::array<double, 2 + 2 * kHarmonicOrders>;
using SampleWaves = std::array<Wave, 3>;  // per joint

// The waves of the three raw readings of a sample (constant through a fit:
// computed once, not in every pass).
SampleWaves reading_waves(const Eigen::Vector3d& raw, const MotionModel& model) {
  SampleWaves w{};
  for (int k = 0; k < 3; ++k) {
    Wave& v = w[static_cast<std::size_t>(k)];
    v[0] = std::sin(raw[k]), v[1] = std::cos(raw[k]);
    for (std::size_t o = 0; o < kHarmonicOrders; ++o) {
      const double a = harmonic_angle(static_cast<int>(o), raw[k], model.gear_ratio, model.cogging_periods);
      v[2 + 2 * o] = std::sin(a), v[3 + 2 * o] = std::cos(a);
    }
  }
  return w;
}

struct SampleRegressors {
  Eigen::Vector3d omega, tau, fric, clr, nb;
  SampleWaves wave;  // of the raw readings (the cyclic errors)
  Eigen::Vector3d flank;
  Eigen::Vector3d hyst, hyst_slope, hyst_threshold;  // g_i, T_i g_i' and T_i (hysteresis_regressors)
};

// One row of the nuisance Jacobian, every column, from the reading
// sensitivities u and the sample's regressors x (calib/motion_correction.hpp).
std::array<double, kNuisance> nuisance_row(const Eigen::Vector3d& u, const SampleRegressors& x) {
  std::array<double, kNuisance> row{};
  row[kSkew] = u[1] * x.omega[1];
  row[kSkew + 1] = u[2] * x.omega[2];
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    row[kCompliance + k] = -u[i] * (x.tau[i] + x.hyst_threshold[i] * x.hyst_slope[i]);
    row[kFriction + k] = u[i] * x.fric[i];
    row[kClearance + k] = u[i] * x.clr[i];
    row[kBefore + k] = -u[i] * x.nb[i];
    const Wave& w = x.wave[k];
    row[kFirstCyclic + k] = -u[i] * w[0];
    row[kFirstCyclic + 3 + k] = -u[i] * w[1];
    row[kBacklash + k] = -u[i] * x.flank[i];
    for (std::size_t o = 0; o < kHarmonicOrders; ++o) {
      row[kHarmonic + 6 * o + k] = -u[i] * w[2 + 2 * o];
      row[kHarmonic + 6 * o + 3 + k] = -u[i] * w[3 + 2 * o];
    }
    row[kHysteresis + k] = u[i] * (x.hyst[i] + x.hyst_slope[i]);
  }
  return row;
}

// The rows of the cyclic error's prior (MotionModel::cyclic_prior_rad) for
// the columns cols after `first` others: each coefficient a_k, b_k ~ N(0,
// prior^2) is one more residual (sigma / prior) (value - 0) at noise sigma.
// Appends them to J (rows) and, with values, to r.
void append_cyclic_prior(const std::vector<int>& cols, Eigen::Index first, double weight, Eigen::MatrixXd& J,
                         Eigen::VectorXd* r, const std::array<double, kNuisance>* values) {
  std::vector<int> at;
  for (std::size_t c = 0; c < cols.size(); ++c)
    if (cols[c] >= kFirstCyclic && cols[c] < kBacklash) at.push_back(static_cast<int>(c));
  if (at.empty()) return;
  const Eigen::Index n = J.rows(), extra = static_cast<Eigen::Index>(at.size());
  J.conservativeResize(n + extra, Eigen::NoChange);
  J.bottomRows(extra).setZero();
  if (r) r->conservativeResize(n + extra);
  for (Eigen::Index k = 0; k < extra; ++k) {
    const Eigen::Index col = first + at[static_cast<std::size_t>(k)];
    J(n + k, col) = weight;
    if (r) (*r)[n + k] = weight * (*values)[static_cast<std::size_t>(cols[static_cast<std::size_t>(at[static_cast<std::size_t>(k)])])];
  }
}

// The nuisance columns of model that the samples excite (calibrate_in_motion).
std::vector<int> excited_columns(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                 const std::vector<Eigen::Vector3d>& tau, const std::vector<Eigen::Vector3d>& fric,
                                 const std::vector<Eigen::Vector3d>& clr, const std::vector<Eigen::Vector3d>& nb,
                                 const std::vector<Eigen::Vector3d>& flank, const std::vector<Eigen::Vector3d>& hyst) {
  const std::size_t n = omega.size();
  auto regressor = [&](int c, std::size_t j) {
    if (c < 2) return omega[j][c + 1];
    if (c < 5) return tau[j][c - 2] - tau[0][c - 2];
    if (c < 8) return model.friction ? fric[j][c - 5] : 0.0;
    if (c < 11) return clr[j][c - 8];
    if (c < kFirstCyclic) return nb.empty() ? 0.0 : nb[j][c - 11] - nb[0][c - 11];
    return 1.0;  // the cyclic errors: a harmonic of the reading itself
  };
  // A value whose regressor takes both signs, each in at least kMinSignShare
  // of the samples (a play or a flank that never changes is a constant, held
  // by lb_i or dth_i).
  const auto both_signs = [&](const std::vector<Eigen::Vector3d>& v, int i) {
    double pos = 0.0, neg = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      if (v[j][i] > 0.0) pos += 1.0;
      if (v[j][i] < 0.0) neg += 1.0;
    }
    return std::min(pos, neg) >= kMinSignShare * static_cast<double>(n) ? 1.0 : 0.0;
  };
  std::vector<int> cols;
  for (int c : nuisance_columns(model)) {
    double excitation = 0.0;
    for (std::size_t j = 0; j < n; ++j) excitation += std::abs(regressor(c, j));
    if (c >= kClearance && c < kClearance + 3) excitation = both_signs(clr, c - kClearance);
    if (c >= kBacklash && c < kBacklash + 3) excitation = both_signs(flank, c - kBacklash);
    if (c >= kHysteresis) excitation = both_signs(hyst, c - kHysteresis);
    if (excitation > 0.0) cols.push_back(c);
  }
  return cols;
}

// The motor-side friction regressors tanh(omega / v_F) (v_F = model.load.friction_speed_rad_s; 0 without model.friction).
std::vector<Eigen::Vector3d> friction_regressors(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega) {
  std::vector<Eigen::Vector3d> fric(omega.size(), Eigen::Vector3d::Zero());
  if (model.friction)
    for (std::size_t j = 0; j < omega.size(); ++j) fric[j] = (omega[j] / model.load.friction_speed_rad_s).array().tanh();
  return fric;
}

// The torques transmitted to the active links (0 without model.clearance).
std::vector<Eigen::Vector3d> transmitted_torques(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                                 const std::vector<Eigen::Vector3d>& tau,
                                                 const std::vector<Eigen::Vector3d>& alpha) {
  std::vector<Eigen::Vector3d> tau_t(omega.size(), Eigen::Vector3d::Zero());
  if (model.clearance)
    for (std::size_t j = 0; j < omega.size(); ++j)
      for (int i = 0; i < 3; ++i)
        tau_t[j][i] = transmitted_torque(model.load, i, tau[j][i], omega[j][i], alpha.empty() ? 0.0 : alpha[j][i]);
  return tau_t;
}

// The sign of each mesh's torque (MotionModel::backlash), 0 where it is
// below model.backlash_torque_min_Nm or the joint has no backlash estimated.
std::vector<Eigen::Vector3d> flank_regressors(const MotionModel& model, const std::vector<Eigen::Vector3d>& omega,
                                              const std::vector<Eigen::Vector3d>& tau,
                                              const std::vector<Eigen::Vector3d>& alpha) {
  const std::vector<Eigen::Vector3d> mesh = mesh_torques(model.load, omega, tau, alpha);
  std::vector<Eigen::Vector3d> flank(omega.size(), Eigen::Vector3d::Zero());
  for (std::size_t j = 0; j < omega.size(); ++j)
    for (int i = 0; i < 3; ++i)
      if (model.backlash[static_cast<std::size_t>(i)] && std::abs(mesh[j][i]) >= model.backlash_torque_min_Nm)
        flank[j][i] = mesh[j][i] > 0.0 ? 1.0 : -1.0;
  return flank;
}

// The mesh torque of each sample where model estimates a hysteresis (0 elsewhere).
std::vector<Eigen::Vector3d> hysteresis_mesh_torques(const MotionModel& model,
                                                     const std::vector<Eigen::Vector3d>& omega,
                                                     const std::vector<Eigen::Vector3d>& tau,
                                                     const std::vector<Eigen::Vector3d>& alpha) {
  std::vector<Eigen::Vector3d> mesh = mesh_torques(model.load, omega, tau, alpha);
  for (Eigen::Vector3d& m : mesh)
    for (int i = 0; i < 3; ++i)
      if (!model.hysteresis[static_cast<std::size_t>(i)]) m[i] = 0.0;
  return mesh;
}

// Passes added to MotionModel::max_passes where a hysteresis is estimated.
constexpr int kHysteresisPasses = 6;

// Largest hysteresis threshold, as a share of the mesh torque's range: the
// element slides from one end to the other over 4 T of torque.
constexpr double kMaxThresholdShare = 0.25;

// Smallest half loss (rad) a hysteresis threshold is made of (an estimate at or below 0 included).
constexpr double kHysteresisMinRad = 3e-6;

// The hysteresis's regressors at the samples `at` of the whole sequence of
// mesh torques: per joint the state g_i = hysteresis_state(mesh torques,
// T_i), T_i = eta_i / c_i, and its response T_i dg_i/dT_i to the threshold
// (a forward difference), which the columns of eta_i and c_i carry: the
// correction eta g(eta / c) moves by g + T g' per unit eta and by -T^2 g' per
// unit c (calib/motion_correction.hpp, MotionModel::hysteresis).
struct HysteresisRegressors {
  std::vector<Eigen::Vector3d> g, slope;  // g_i and T_i g_i' per sample
  Eigen::Vector3d threshold = Eigen::Vector3d::Zero();  // T_i (N m)
};

// Joint i's mesh torques over the whole sequence.
std::vector<double> joint_torques(const std::vector<Eigen::Vector3d>& mesh, int i) {
  std::vector<double> t(mesh.size());
  for (std::size_t j = 0; j < mesh.size(); ++j) t[j] = mesh[j][i];
  return t;
}

// The thresholds T_i = eta_i / c_i (N m) of the joints with a hysteresis (c_i
// the estimate, or model's where none): within a factor 2 of the previous
// ones (> 0: a Gauss-Newton step on a regressor whose shape it moves), and at
// most a quarter of the torque's range (beyond it the element never slides
// from one end to the other: g is the torque's, the compliance's, own).
Eigen::Vector3d hysteresis_thresholds(const MotionModel& model, const std::vector<Eigen::Vector3d>& mesh,
                                      const std::array<double, 3>& eta, const std::array<double, 3>& compliance,
                                      const Eigen::Vector3d& previous) {
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!model.hysteresis[k] || mesh.empty()) continue;
    const double c = compliance[k] > 0.0 ? compliance[k] : model.hysteresis_compliance_rad_per_Nm;
    T[i] = std::max(eta[k], kHysteresisMinRad) / c;
    if (previous[i] > 0.0) T[i] = std::clamp(T[i], 0.5 * previous[i], 2.0 * previous[i]);
    const auto [lo, hi] = std::ranges::minmax(joint_torques(mesh, i));
    T[i] = std::min(T[i], largest_hysteresis_threshold(hi - lo));
  }
  return T;
}

// The thresholds where the fit starts: starting_hysteresis_threshold, within each torque's range.
Eigen::Vector3d starting_thresholds(const MotionModel& model, const std::vector<Eigen::Vector3d>& mesh) {
  const double eta0 = model.hysteresis_start_rad;
  return hysteresis_thresholds(model, mesh, {eta0, eta0, eta0}, {}, Eigen::Vector3d::Zero());
}

HysteresisRegressors hysteresis_regressors(const MotionModel& model, const std::vector<Eigen::Vector3d>& mesh,
                                           const std::vector<std::size_t>& at, const Eigen::Vector3d& threshold) {
  constexpr double kRelativeStep = 1e-3;
  HysteresisRegressors h{std::vector<Eigen::Vector3d>(at.size(), Eigen::Vector3d::Zero()),
                         std::vector<Eigen::Vector3d>(at.size(), Eigen::Vector3d::Zero()), threshold};
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> t = joint_torques(mesh, i);
    if (!model.hysteresis[static_cast<std::size_t>(i)] || t.empty()) continue;
    const std::vector<double> g = hysteresis_state(t, h.threshold[i]);
    const std::vector<double> g_up = hysteresis_state(t, h.threshold[i] * (1.0 + kRelativeStep));
    const auto [lo, hi] = std::ranges::minmax(t);
    const bool held = h.threshold[i] >= largest_hysteresis_threshold(hi - lo) * (1.0 - 1e-9);  // at its bound: fixed
    for (std::size_t j = 0; j < at.size(); ++j) {
      h.g[j][i] = g[at[j]];
      h.slope[j][i] = held ? 0.0 : (g_up[at[j]] - g[at[j]]) / kRelativeStep;
    }
  }
  return h;
}

// The samples calibrate_in_motion keeps: after the first model.skip_first,
// those whose clearance regressors are all certain (with drop_uncertain) and
// whose meshes' flanks are certain where a backlash is estimated.
std::vector<std::size_t> kept_samples(const MotionModel& model, const std::vector<Eigen::Vector3d>& clr,
                                      const std::vector<Eigen::Vector3d>& flank) {
  std::vector<std::size_t> kept;
  for (std::size_t j = static_cast<std::size_t>(std::max(0, model.skip_first)); j < clr.size(); ++j) {
    bool ok = !(model.clearance && model.drop_uncertain) || (clr[j].array() != 0.0).all();
    for (int i = 0; i < 3; ++i) ok = ok && (!model.backlash[static_cast<std::size_t>(i)] || flank[j][i] != 0.0);
    if (ok) kept.push_back(j);
  }
  return kept;
}

}  // namespace

std::vector<Eigen::Vector3d> correct_readings(const std::vector<Eigen::Vector3d>& theta_m,
                                              const std::vector<Eigen::Vector3d>& omega,
                                              const std::vector<Eigen::Vector3d>& tau,
                                              const std::array<double, 5>& nu) {
  std::vector<Eigen::Vector3d> out(theta_m.size());
  for (std::size_t j = 0; j < theta_m.size(); ++j) {
    const Eigen::Vector3d s(0.0, nu[0], nu[1]), c(nu[2], nu[3], nu[4]);
    out[j] = theta_m[j] + s.cwiseProduct(omega[j]) - c.cwiseProduct(tau[j]);
  }
  return out;
}

namespace {

// The noise model's 1-sigma slot of MotionFit that nuisance column k fills (nullptr: none kept).
double* noise_sigma_slot(MotionFit& fit, int k) {
  const auto at = [k](int first) { return static_cast<std::size_t>(k - first); };
  if (k >= kClearance && k < kBefore) return &fit.noise_sigma.clearance[at(kClearance)];
  if (k >= kBefore && k < kFirstCyclic) return &fit.noise_sigma.torque_before[at(kBefore)];
  if (k >= kBacklash && k < kHarmonic) return &fit.noise_sigma.backlash[at(kBacklash)];
  if (k >= kHysteresis) return &fit.noise_sigma.hysteresis[at(kHysteresis)];
  if (k >= kHarmonic) return &fit.noise_sigma.harmonic[at(kHarmonic) / 6][at(kHarmonic) % 6];
  return nullptr;
}

// The 1-sigma slot of MotionFit that nuisance column k fills.
double& nuisance_sigma_slot(MotionFit& fit, int k) {
  const auto at = [k](int first) { return static_cast<std::size_t>(k - first); };
  if (k < kFriction) return fit.nu_sigma[at(kSkew)];
  if (k < kClearance) return fit.friction_sigma[at(kFriction)];
  if (k < kBefore) return fit.clearance_sigma[at(kClearance)];
  if (k < kFirstCyclic) return fit.torque_before_sigma[at(kBefore)];
  if (k < kBacklash) return fit.cyclic_sigma[at(kFirstCyclic)];
  if (k < kHarmonic) return fit.backlash_sigma[at(kBacklash)];
  if (k >= kHysteresis) return fit.hysteresis_sigma[at(kHysteresis)];
  return fit.harmonic_sigma[at(kHarmonic) / 6][at(kHarmonic) % 6];
}

// True when chi2 for dof degrees of freedom exceeds the noise alone at the
// model test's level, 1 % (calib/model_test.hpp: a test that fails widens the
// 1-sigma). Not with what the samples' doubt adds, as the test has it: the
// twist a resting joint holds is one value over many samples, and an
// estimate it moves (a harmonic of the joint angle most) moves with it, which
// the weights, independent per sample, do not state; the sandwich, from the
// residuals' autocorrelation, does, and is taken where it is wider.
bool misfit(double chi2, double dof) { return chi2_survival(dof, chi2) < 1e-2; }

// Bartlett bandwidth L of Andrews (1991) for residuals r along the path,
// modelled as AR(1) with coefficient rho (their lag-1 autocorrelation):
// L = 1.1447 (alpha n)^(1/3), alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2);
// at most n / 2.
int andrews_bandwidth(const Eigen::VectorXd& r) {
  const Eigen::Index n = r.size();
  if (n < 3) return 0;
  const double rho = std::clamp(r.head(n - 1).dot(r.tail(n - 1)) / r.head(n - 1).squaredNorm(), -0.999, 0.999);
  const double alpha = 4.0 * rho * rho / ((1.0 - rho) * (1.0 - rho) * (1.0 + rho) * (1.0 + rho));
  const double L = 1.1447 * std::cbrt(alpha * static_cast<double>(n));
  return static_cast<int>(std::min(std::floor(L), static_cast<double>(n / 2)));
}

// The autocorrelation-consistent (Newey-West, Bartlett weights 1 - |l| / (L + 1))
// covariance of the least-squares estimate with (J'J)^-1 = A and residuals r
// along the path: A B A, B = sum_{j,k} (1 - |j - k| / (L + 1))_+ g_j g_k',
// g_j = J_j' r_j, L = andrews_bandwidth(r). B is summed as the windows of
// L + 1 consecutive g (every window that overlaps the path, partial ones at
// its ends): sum_t S_t S_t' / (L + 1), which is O(n) for any L.
Eigen::MatrixXd newey_west_sandwich(const Eigen::MatrixXd& A, const Eigen::MatrixXd& J, const Eigen::VectorXd& r) {
  const Eigen::Index n = J.rows(), m = J.cols();
  const int L = andrews_bandwidth(r);
  Eigen::MatrixXd prefix = Eigen::MatrixXd::Zero(n + 1, m);  // row k: sum of g_j, j < k
  for (Eigen::Index j = 0; j < n; ++j) prefix.row(j + 1) = prefix.row(j) + r[j] * J.row(j);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index t = -L; t < n; ++t) {
    const Eigen::RowVectorXd S = prefix.row(std::min(n, t + L + 1)) - prefix.row(std::max<Eigen::Index>(0, t));
    B.noalias() += S.transpose() * S;
  }
  return A * (B / (L + 1.0)) * A;
}

// The samples of one fit in motion (one entry per sample each): raw readings
// theta_m (rad), joint speeds omega, drive torques tau, their changes nb
// (torques_before; empty: none) and accelerations alpha (empty: 0).
struct MotionSamples {
  const std::vector<Eigen::Vector3d>& theta_m;
  const std::vector<Eigen::Vector3d>& omega;
  const std::vector<Eigen::Vector3d>& tau;
  const std::vector<Eigen::Vector3d>& nb;
  const std::vector<Eigen::Vector3d>& alpha;
};

// The regressors of the reading effects over the samples (see SampleRegressors),
// the clearance's at the start geometry and with its force threshold.
struct EffectRegressors {
  std::vector<Eigen::Vector3d> fric, tau_t, clr, flank;
  HysteresisRegressors hyst;
  std::vector<Eigen::Vector3d> mesh;  // the mesh torques of the whole sequence (hysteresis_state runs on it)
  std::vector<std::size_t> at;        // each regressor's sample in mesh
  std::vector<SampleWaves> wave;  // of the raw readings
  // Per sample and chain, what a wrong force sign adds to the reading's
  // variance per mm^2 of play (sign_flip_variance; 0 where the sign is not used).
  std::vector<Eigen::Vector3d> flip;
  double tension_min = 0.0;
};

// Throws InputError when the samples' sizes differ or the cost is not ML.
void check_motion_inputs(const MotionSamples& s, const LmOptions& options) {
  const std::size_t n = s.theta_m.size();
  if (s.omega.size() != n || s.tau.size() != n)
    throw InputError(fmt::format("calibration in motion: {} readings but {} joint speeds and {} torques", n,
                                 s.omega.size(), s.tau.size()));
  if (options.cost != Cost::kML)
    throw InputError("calibration in motion: the reading corrections need the ML cost (--cost ml)");
  if (!s.alpha.empty() && s.alpha.size() != n)
    throw InputError(fmt::format("calibration in motion: {} readings but {} joint accelerations", n, s.alpha.size()));
}

// The clearance's regressors and its signs' doubts (e.clr, e.flip) from the
// passive links' forces, at the threshold e.tension_min.
void set_force_signs(const std::vector<std::optional<PassiveForces>>& forces, const MotionModel& model,
                     const std::vector<Eigen::Vector3d>& omega, EffectRegressors& e) {
  e.clr = clearance_regressors(forces, e.tension_min);
  e.flip = flip_variances(forces, e.tension_min, model, omega);
}

// The force signs of the samples in which a passive link may be crossing its
// play (calib/play_crossing.hpp) made uncertain: their clearance regressors
// and signs' doubts 0, as below the force threshold.
void leave_crossings_uncertain(const std::vector<std::optional<PassiveForces>>& forces, int samples, EffectRegressors& e) {
  std::vector<std::optional<Eigen::Vector3d>> tension(forces.size());
  for (std::size_t j = 0; j < forces.size(); ++j)
    if (forces[j]) tension[j] = forces[j]->tension;
  const std::vector<std::array<bool, 3>> crossing = play_crossing(tension, samples);
  for (std::size_t j = 0; j < forces.size(); ++j)
    for (int i = 0; i < 3; ++i)
      if (crossing[j][static_cast<std::size_t>(i)]) e.clr[j][i] = e.flip[j][i] = 0.0;
}

// EffectRegressors of samples s for model at geometry start.
EffectRegressors effect_regressors(const Geometry& start, const MotionSamples& s, const MotionModel& model) {
  EffectRegressors e;
  // Coulomb friction F_i on the motor side of the transmission: the
  // transmitted torque is tau_i - F_i sign(omega_i), so the link twists by
  // c_i F_i sign(omega_i) less than c_i tau_i says (the sign smoothed over
  // model.load.friction_speed_rad_s, within which the friction builds up).
  e.fric = friction_regressors(model, s.omega);
  e.tau_t = transmitted_torques(model, s.omega, s.tau, s.alpha);
  std::vector<std::optional<PassiveForces>> forces;
  if (model.clearance) forces = passive_forces(start, s.theta_m, e.tau_t);
  e.tension_min = effective_tension_min(model, forces);
  e.clr.assign(s.theta_m.size(), Eigen::Vector3d::Zero());
  e.flip = e.clr;
  if (model.clearance) set_force_signs(forces, model, s.omega, e);
  if (model.clearance && model.crossing_samples > 0) leave_crossings_uncertain(forces, model.crossing_samples, e);
  e.flank = flank_regressors(model, s.omega, s.tau, s.alpha);
  e.mesh = hysteresis_mesh_torques(model, s.omega, s.tau, s.alpha);
  e.at.resize(s.theta_m.size());
  std::iota(e.at.begin(), e.at.end(), std::size_t{0});
  e.hyst = hysteresis_regressors(model, e.mesh, e.at, starting_thresholds(model, e.mesh));
  return e;  // the waves are the fit's (fit_in_motion), on the samples it keeps
}

// The regressors of the samples kept (indices into e's), per sample as
// effect_regressors would compute them on those samples alone.
EffectRegressors kept_regressors(const EffectRegressors& e, const std::vector<std::size_t>& kept) {
  EffectRegressors k;
  k.tension_min = e.tension_min;
  k.mesh = e.mesh;
  k.hyst.threshold = e.hyst.threshold;
  for (std::size_t j : kept) {
    k.hyst.g.push_back(e.hyst.g[j]);
    k.hyst.slope.push_back(e.hyst.slope[j]);
    k.at.push_back(e.at[j]);
    k.fric.push_back(e.fric[j]);
    k.tau_t.push_back(e.tau_t[j]);
    k.clr.push_back(e.clr[j]);
    k.flip.push_back(e.flip[j]);
    k.flank.push_back(e.flank[j]);
  }
  return k;
}

// A MotionFit with every nuisance 1-sigma NaN (not estimated).
MotionFit unestimated_fit() {
  MotionFit fit;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  fit.nu_sigma.fill(nan);
  fit.friction_sigma.fill(nan);
  fit.clearance_sigma.fill(nan);
  fit.torque_before_sigma.fill(nan);
  fit.cyclic_sigma.fill(nan);
  fit.backlash_sigma.fill(nan);
  fit.hysteresis_sigma.fill(nan);
  for (auto& h : fit.harmonic_sigma) h.fill(nan);
  fit.noise_sigma.clearance = fit.clearance_sigma;
  fit.noise_sigma.torque_before = fit.torque_before_sigma;
  fit.noise_sigma.backlash = fit.backlash_sigma;
  fit.noise_sigma.hysteresis = fit.hysteresis_sigma;
  fit.noise_sigma.harmonic = fit.harmonic_sigma;
  return fit;
}

// The nuisance vector (layout kSkew ... kHarmonic) written into fit's named values.
void unpack_nuisance(const std::array<double, kNuisance>& nu_all, MotionFit& fit) {
  const auto at = [&nu_all](int first) { return nu_all.begin() + first; };
  std::copy_n(at(kSkew), 5, fit.nu.begin());  // the skews and the compliances
  std::copy_n(at(kFriction), 3, fit.friction.begin());
  std::copy_n(at(kClearance), 3, fit.clearance.begin());
  std::copy_n(at(kBefore), 3, fit.torque_before.begin());
  std::copy_n(at(kFirstCyclic), 6, fit.cyclic.begin());
  std::copy_n(at(kBacklash), 3, fit.backlash.begin());
  std::copy_n(at(kHysteresis), 3, fit.hysteresis.begin());
  for (std::size_t o = 0; o < kHarmonicOrders; ++o)
    std::copy_n(at(kHarmonic + 6 * static_cast<int>(o)), 6, fit.harmonic[o].begin());
}

// The readings of s corrected with fit's nuisance values for the twist, skew,
// friction, torque change, cyclic error, backlash and harmonics (not the clearance).
std::vector<Eigen::Vector3d> twist_corrected(const MotionFit& fit, const MotionSamples& s, const EffectRegressors& e) {
  std::vector<Eigen::Vector3d> out = correct_readings(s.theta_m, s.omega, s.tau, fit.nu);
  for (std::size_t j = 0; j < out.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const Wave& w = e.wave[j][i];
      out[j][k] += fit.friction[i] * e.fric[j][k];
      if (!s.nb.empty()) out[j][k] -= fit.torque_before[i] * s.nb[j][k];
      out[j][k] -= fit.cyclic[i] * w[0] + fit.cyclic[i + 3] * w[1];
      out[j][k] -= fit.backlash[i] * e.flank[j][k];
      out[j][k] += fit.hysteresis[i] * e.hyst.g[j][k];
      for (std::size_t o = 0; o < kHarmonicOrders; ++o)
        out[j][k] -= fit.harmonic[o][i] * w[2 + 2 * o] + fit.harmonic[o][i + 3] * w[3 + 2 * o];
    }
  return out;
}

// twist_corrected plus the clearance d_i times its regressors.
std::vector<Eigen::Vector3d> fully_corrected(const MotionFit& fit, const MotionSamples& s, const EffectRegressors& e) {
  std::vector<Eigen::Vector3d> out = twist_corrected(fit, s, e);
  for (std::size_t j = 0; j < out.size(); ++j)
    for (int k = 0; k < 3; ++k) out[j][k] += fit.clearance[static_cast<std::size_t>(k)] * e.clr[j][k];
  return out;
}

// Row `row` of the nuisance Jacobian (excited columns cols) into Jn and of the
// six cyclic columns into Jc, from the sample's reading sensitivities u.
void fill_nuisance_row(const Eigen::Vector3d& u, const SampleRegressors& reg, const std::vector<int>& cols,
                       Eigen::Index row, Eigen::MatrixXd& Jn, Eigen::MatrixXd& Jc, Eigen::Index first = 0) {
  const std::array<double, kNuisance> all = nuisance_row(u, reg);
  for (std::size_t c = 0; c < cols.size(); ++c)
    Jn(row, first + static_cast<Eigen::Index>(c)) = all[static_cast<std::size_t>(cols[c])];
  for (int c = 0; c < 6; ++c) Jc(row, c) = all[static_cast<std::size_t>(kFirstCyclic + c)];
}

// The fit's linearisation at one geometry: the free geometry columns Jg, the
// excited nuisance columns Jn, the cyclic columns Jc, the ML residuals r and
// each sample's reading sensitivities U (a row each, reading_sensitivity).
struct Linearisation {
  Eigen::MatrixXd Jg, Jn, Jc;
  Eigen::VectorXd r;
  Eigen::MatrixXd U;
  Eigen::VectorXd w;  // the samples' weights, applied to the rows of Jg, Jn, Jc and r (not U)
};

// Linearisation at geometry g of the corrected readings th (raw readings and
// regressors from s and e), for the free parameters free_index and columns
// cols, each sample's rows weighted by w (empty: 1).
Linearisation linearise(const Geometry& g, const std::vector<Eigen::Vector3d>& th, const MotionSamples& s,
                        const EffectRegressors& e, const std::vector<int>& free_index, const std::vector<int>& cols,
                        const std::vector<double>& w = {}) {
  const auto n = static_cast<Eigen::Index>(th.size());
  const ParamVector x = to_solver(g, Cost::kML);
  const Eigen::MatrixXd J_all = ml_jacobian(th, g);
  Linearisation l{Eigen::MatrixXd(n, static_cast<Eigen::Index>(free_index.size())),
                  Eigen::MatrixXd(n, static_cast<Eigen::Index>(cols.size())), Eigen::MatrixXd(n, 6), Eigen::VectorXd(n),
                  Eigen::MatrixXd(n, 3), Eigen::VectorXd::Ones(n)};
  for (std::size_t k = 0; k < free_index.size(); ++k) l.Jg.col(static_cast<Eigen::Index>(k)) = J_all.col(free_index[k]);
  for (std::size_t j = 0; j < th.size(); ++j) {
    l.r[static_cast<Eigen::Index>(j)] = ml_residual(x, th[j]);
    const SampleRegressors reg{s.omega[j], s.tau[j], e.fric[j], e.clr[j], s.nb.empty() ? Eigen::Vector3d::Zero() : s.nb[j],
                               e.wave[j], e.flank[j], e.hyst.g[j], e.hyst.slope[j], e.hyst.threshold};
    const Eigen::Vector3d u = reading_sensitivity(J_all, j);
    l.U.row(static_cast<Eigen::Index>(j)) = u.transpose();
    fill_nuisance_row(u, reg, cols, static_cast<Eigen::Index>(j), l.Jn, l.Jc);
  }
  if (!w.empty()) l.w = Eigen::Map<const Eigen::VectorXd>(w.data(), n);
  l.r.array() *= l.w.array();
  l.Jg = l.w.asDiagonal() * l.Jg;
  l.Jn = l.w.asDiagonal() * l.Jn;
  l.Jc = l.w.asDiagonal() * l.Jc;
  return l;
}

// rest_twist_variance of each joint at rates omega with twists c_i F_i (rad) and stick speed v_s.
Eigen::Vector3d rest_variances(const Eigen::Vector3d& omega, const std::array<double, 3>& twist, double v_s) {
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    v[k] = rest_twist_variance(omega[k], twist[i], v_s);
  }
  return v;
}

// The samples' weights for the next pass (calib/sample_weights.hpp) from the
// reading sensitivities U, the friction twists and plays fit estimated so far
// and the force signs' doubts e.flip; empty (all 1) without a stick speed or
// a force's 1-sigma, or without the reading noise.
std::vector<double> fit_weights(const MotionModel& model, const LmOptions& options, const Eigen::MatrixXd& U,
                                const std::vector<Eigen::Vector3d>& omega, const EffectRegressors& e,
                                const MotionFit& fit) {
  const bool rest = model.stick_speed_rad_s > 0.0, signs = model.tension_sigma_N > 0.0 && e.flip.size() == omega.size();
  if (!(rest || signs) || !options.encoder_sigma || U.rows() != static_cast<Eigen::Index>(omega.size())) return {};
  std::vector<double> w(omega.size(), 1.0);
  for (std::size_t j = 0; j < omega.size(); ++j) {
    Eigen::Vector3d v = rest ? rest_variances(omega[j], fit.friction, model.stick_speed_rad_s) : Eigen::Vector3d::Zero();
    for (std::size_t i = 0; signs && i < 3; ++i)
      v[static_cast<Eigen::Index>(i)] += fit.clearance[i] * fit.clearance[i] * e.flip[j][static_cast<Eigen::Index>(i)];
    w[j] = sample_weight(U.row(static_cast<Eigen::Index>(j)).transpose(), v, *options.encoder_sigma);
  }
  return w;
}

// The largest change between weights a and b (empty: all 1).
double weight_change(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t j = 0; j < std::max(a.size(), b.size()); ++j)
    d = std::max(d, std::abs((j < a.size() ? a[j] : 1.0) - (j < b.size() ? b[j] : 1.0)));
  return d;
}

// The doubt the model test expects (calib/model_test.hpp SampleDoubt) of the
// samples at l (their rates omega): where a joint may rest, its twist within
// +-c F, c the data sheet's compliance and F the drive friction the
// calibration takes (model.load), not the fitted twist c F, which a misfit
// where the joints are slow would inflate with its doubt. All 0 without a
// stick speed or the reading noise.
SampleDoubt stated_doubt(const MotionModel& model, const LmOptions& options, const Linearisation& l,
                         const std::vector<Eigen::Vector3d>& omega) {
  const auto n = static_cast<Eigen::Index>(omega.size());
  if (!(model.stick_speed_rad_s > 0.0) || !options.encoder_sigma || l.U.rows() != n) return {};
  std::array<double, 3> twist{};  // c F
  for (std::size_t i = 0; i < 3; ++i) twist[i] = model.hysteresis_compliance_rad_per_Nm * model.load.coulomb_Nm[i];
  Eigen::VectorXd w(n);
  for (Eigen::Index j = 0; j < n; ++j)
    w[j] = sample_weight(l.U.row(j).transpose(),
                         rest_variances(omega[static_cast<std::size_t>(j)], twist, model.stick_speed_rad_s),
                         *options.encoder_sigma);
  return sample_doubt(w);
}

// [Jg, Jn] with the cyclic prior's rows (append_cyclic_prior).
Eigen::MatrixXd joint_jacobian(const Linearisation& l, const std::vector<int>& cols, double prior_weight) {
  Eigen::MatrixXd J(l.r.size(), l.Jg.cols() + l.Jn.cols());
  J << l.Jg, l.Jn;
  append_cyclic_prior(cols, l.Jg.cols(), prior_weight, J, nullptr, nullptr);
  return J;
}

// One joint Gauss-Newton step of geometry and nuisance values at l, applied
// to nu_all; returns the largest change of the residuals it makes, as a
// fraction of |r| (column-scaled: seconds, rad/N m and mm differ by orders).
double nuisance_step(const Linearisation& l, const std::vector<int>& cols, double prior_weight,
                     std::array<double, kNuisance>& nu_all) {
  Eigen::MatrixXd J(l.r.size(), l.Jg.cols() + l.Jn.cols());
  J << l.Jg, l.Jn;
  Eigen::VectorXd rp = l.r;
  append_cyclic_prior(cols, l.Jg.cols(), prior_weight, J, &rp, &nu_all);
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c) scale[c] = scale[c] > 0.0 ? scale[c] : 1.0;
  const Eigen::MatrixXd Js = J * scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd step = scale.cwiseInverse().asDiagonal() * Js.colPivHouseholderQr().solve(-rp);
  double change = 0.0;
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const Eigen::Index i = l.Jg.cols() + static_cast<Eigen::Index>(c);
    nu_all[static_cast<std::size_t>(cols[c])] += step[i];
    change = std::max(change, std::abs(step[i]) * scale[i] / (l.r.norm() + 1e-300));
  }
  return change;
}

// Every LM iteration of every pass, numbered on (the report's convergence
// figure): appends pass to all.
void append_iterations(std::vector<LmIteration>& all, const std::vector<LmIteration>& pass) {
  const int next = all.empty() ? 0 : all.back().iteration + 1;
  for (LmIteration it : pass) {
    it.iteration += next;
    all.push_back(it);
  }
}

// The 15 x 15 covariance whose free rows and columns (free_index) are the
// leading block of C, zero elsewhere.
Eigen::Matrix<double, kNumParams, kNumParams> scatter_free(const Eigen::MatrixXd& C, const std::vector<int>& free_index) {
  Eigen::Matrix<double, kNumParams, kNumParams> cov = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (std::size_t a = 0; a < free_index.size(); ++a)
    for (std::size_t b = 0; b < free_index.size(); ++b)
      cov(free_index[a], free_index[b]) = C(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  return cov;
}

// The chi-square the carried columns l.Jc explain of l.r within their prior
// (calib::carried_chi2), the fitted columns J (A = (J' J)^-1) projected out
// of them: Gp = (I - J A J') Jc.
double carried_chi2_of(const Eigen::MatrixXd& A, const Eigen::MatrixXd& J, const Linearisation& l, double prior,
                       double s2) {
  const Eigen::MatrixXd Jr = J.topRows(l.r.size());
  return carried_chi2(l.Jc - Jr * (A * (Jr.transpose() * l.Jc)), l.r, prior, s2);
}

// r'r of l's residuals with the samples' weights taken off (r over w): as
// the encoders' noise alone judges them.
double unweighted_norm2(const Linearisation& l) {
  return l.w.size() == 0 ? l.r.squaredNorm() : l.r.cwiseQuotient(l.w).squaredNorm();
}

// carried_chi2_of for the residuals unweighted, as the model test sums them:
// at l itself (J, A = (J' J)^-1 its fitted columns) when it has no weights,
// else with the rows of Jg, Jn, Jc and r over w and their own columns projected out.
double unweighted_carried_chi2(const Linearisation& l, const Eigen::MatrixXd& A, const Eigen::MatrixXd& J,
                               const std::vector<int>& cols, double prior_weight, double prior, double s2) {
  if (l.w.size() == 0) return carried_chi2_of(A, J, l, prior, s2);
  Linearisation u = l;
  const Eigen::VectorXd inv = l.w.cwiseInverse();
  u.Jg = inv.asDiagonal() * l.Jg;
  u.Jn = inv.asDiagonal() * l.Jn;
  u.Jc = inv.asDiagonal() * l.Jc;
  u.r = l.r.cwiseProduct(inv);
  u.w.resize(0);
  const Eigen::MatrixXd Ju = joint_jacobian(u, cols, prior_weight);
  const Eigen::MatrixXd Au = (Ju.transpose() * Ju).ldlt().solve(Eigen::MatrixXd::Identity(Ju.cols(), Ju.cols()));
  return carried_chi2_of(Au, Ju, u, prior, s2);
}

// The joint covariance sigma^2 (J' J)^-1 of [J_g, J_nu] at l (the misfit's
// sandwich in its place when model.sandwich and the residuals exceed the
// noise; the considered cyclic error added): its geometry block replaces
// fit.result's, its nuisance diagonal gives the nuisance 1-sigma. With
// samples' weights, whether the residuals exceed the noise and what the
// carried error explains of them are judged unweighted, by the noise alone
// as the model test judges them: a weight is a doubt the reading model
// states, and misfit that lies where it weighs less must still widen the
// 1-sigma (the sandwich is of the weighted fit).
void joint_covariance(const Linearisation& l, const std::vector<int>& cols, double prior_weight,
                      const std::vector<int>& free_index, const LmOptions& options, const MotionModel& model,
                      MotionFit& fit) {
  const Eigen::MatrixXd J = joint_jacobian(l, cols, prior_weight);
  const Eigen::Index m = J.cols(), ng = l.Jg.cols();
  const auto q = static_cast<int>(cols.size());
  const double dof = static_cast<double>(l.r.size()) - static_cast<double>(m);
  const double s2 = options.encoder_sigma ? (*options.encoder_sigma) * (*options.encoder_sigma)
                                          : (dof > 0 ? l.r.squaredNorm() / dof : std::numeric_limits<double>::quiet_NaN());
  const Eigen::MatrixXd A = (J.transpose() * J).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  Eigen::MatrixXd C = s2 * A;
  for (int c = 0; c < q; ++c)
    if (double* slot = noise_sigma_slot(fit, cols[static_cast<std::size_t>(c)])) *slot = std::sqrt(C(ng + c, ng + c));
  if (options.encoder_sigma) fit.chi2 = l.r.squaredNorm() / s2;
  if (options.encoder_sigma && dof > 0) fit.chi2_per_dof = fit.chi2 / dof;
  if (considers_cyclic(model) && options.encoder_sigma)
    fit.carried_chi2 = unweighted_carried_chi2(l, A, J, cols, prior_weight, model.cyclic_prior_rad, s2);
  // As the model test judges (calib/model_test.hpp): the unweighted chi-square less what the carried error
  // explains, on the samples' count less the geometry's free parameters; against the noise alone (misfit).
  const double test_dof = static_cast<double>(l.r.size() - ng);
  if (model.sandwich && options.encoder_sigma && dof > 0 &&
      misfit(unweighted_norm2(l) / s2 - fit.carried_chi2, test_dof)) {
    // The residuals exceed the noise: what the model leaves out moves the
    // estimate as much as it moves the residuals, correlated along the path.
    const Eigen::MatrixXd S = newey_west_sandwich(A, J.topRows(l.r.size()), l.r);
    fit.sandwich_inflation = std::sqrt(S.diagonal().head(ng).sum() / C.diagonal().head(ng).sum());
    if (fit.sandwich_inflation > 1.0) C = S, fit.sandwich_used = true;
  }
  if (considers_cyclic(model)) {
    Eigen::MatrixXd carried = Eigen::MatrixXd::Zero(m, m);
    add_considered(A, J, l.Jc, model.cyclic_prior_rad, carried);
    C += carried;
    fit.result.carried_covariance = scatter_free(carried, free_index);
  }
  fit.result.covariance = scatter_free(C, free_index);
  for (std::size_t a = 0; a < free_index.size(); ++a)
    fit.result.sigma[static_cast<std::size_t>(free_index[a])] = std::sqrt(C(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a)));
  for (int c = 0; c < q; ++c) nuisance_sigma_slot(fit, cols[static_cast<std::size_t>(c)]) = std::sqrt(C(ng + c, ng + c));
}

// The indices of the free parameters of mask free.
std::vector<int> free_indices(const FreeMask& free) {
  std::vector<int> out;
  for (int k = 0; k < kNumParams; ++k)
    if (free[k]) out.push_back(k);
  return out;
}

MotionFit fit_in_motion(const Problem& problem, const MotionSamples& s, const LmOptions& options,
                        const MotionModel& model, const EffectRegressors* given = nullptr);

// The nuisance values the passes start from: 0, but a hysteresis at
// model.hysteresis_start_rad and its joint's compliance (where estimated) at
// model.hysteresis_compliance_rad_per_Nm, where its threshold starts.
std::array<double, kNuisance> starting_nuisance(const MotionModel& model, const std::vector<int>& cols) {
  std::array<double, kNuisance> nu{};
  for (int c : cols)
    if (c >= kHysteresis) {
      nu[static_cast<std::size_t>(c)] = model.hysteresis_start_rad;
      if (std::ranges::find(cols, kCompliance + c - kHysteresis) != cols.end())
        nu[static_cast<std::size_t>(kCompliance + c - kHysteresis)] = model.hysteresis_compliance_rad_per_Nm;
    }
  return nu;
}

// fit_in_motion on the samples kept only (indices into s), with the force
// threshold of all of them; the fit's indices and clearance shares are of all.
MotionFit fit_on_kept(const Problem& problem, const MotionSamples& s, const LmOptions& options,
                      const MotionModel& model, const EffectRegressors& e, const std::vector<std::size_t>& kept) {
  const std::size_t n = s.theta_m.size();
  Problem sub = problem;
  sub.theta_m.clear();
  sub.true_xy.clear();
  sub.weight.clear();
  std::vector<Eigen::Vector3d> omega, tau, nb, alpha;
  for (std::size_t j : kept) {
    if (!s.nb.empty()) nb.push_back(s.nb[j]);
    sub.theta_m.push_back(s.theta_m[j]);
    omega.push_back(s.omega[j]);
    tau.push_back(s.tau[j]);
    if (!s.alpha.empty()) alpha.push_back(s.alpha[j]);
    if (problem.true_xy.size() == n) sub.true_xy.push_back(problem.true_xy[j]);
  }
  MotionModel sub_model = model;
  sub_model.skip_first = 0;
  sub_model.drop_uncertain = false;
  sub_model.crossing_samples = 0;  // the kept samples are not consecutive: e's crossings stand
  sub_model.tension_min_N = e.tension_min;
  const EffectRegressors sub_e = kept_regressors(e, kept);  // what the kept samples alone give: not computed again
  MotionFit fit = fit_in_motion(sub, MotionSamples{sub.theta_m, omega, tau, nb, alpha}, options, sub_model, &sub_e);
  for (std::size_t& j : fit.kept) j = kept[j];
  for (std::size_t k = 0; k < 3; ++k) {
    double certain = 0.0;
    for (std::size_t j = 0; j < n; ++j) certain += e.clr[j][static_cast<Eigen::Index>(k)] != 0.0 ? 1.0 : 0.0;
    fit.clearance_used[k] = certain / static_cast<double>(n);
  }
  return fit;
}

// The regressors that move with the estimates, for a pass after the first:
// with the clearance its regressors and its signs' doubts (e.clr, e.flip)
// from the forces at geometry g with the readings corrected for fit's twist
// so far; the hysteresis's threshold eta_i / c_i from the estimates so far,
// whose regressor's shape follows them (a Gauss-Newton step on both, through the slope).
void refresh_regressors(const Geometry& g, const MotionModel& model, const MotionFit& fit, const MotionSamples& s,
                        EffectRegressors& e) {
  if (model.clearance) set_force_signs(passive_forces(g, twist_corrected(fit, s, e), e.tau_t), model, s.omega, e);
  e.hyst = hysteresis_regressors(
      model, e.mesh, e.at,
      hysteresis_thresholds(model, e.mesh, fit.hysteresis, {fit.nu[2], fit.nu[3], fit.nu[4]}, e.hyst.threshold));
}

// calibrate_in_motion on samples s (the torque changes nb given: torques_before
// of the whole sequence; empty without model.torque_before). Passes of an LM
// fit of the geometry on readings corrected with the nuisance values, then a
// joint Gauss-Newton step of both, until the step is negligible.
MotionFit fit_in_motion(const Problem& problem, const MotionSamples& s, const LmOptions& options,
                        const MotionModel& model, const EffectRegressors* given) {
  check_motion_inputs(s, options);
  EffectRegressors e = given ? *given : effect_regressors(problem.start, s, model);
  // Samples left out: the leading ones, and (with the clearance) those in
  // which some chain's force sign is uncertain, and those where a mesh with
  // backlash crosses its gap; the fit runs on the rest.
  std::vector<std::size_t> kept = kept_samples(model, e.clr, e.flank);
  if (kept.size() < s.theta_m.size()) return fit_on_kept(problem, s, options, model, e, kept);
  e.wave.reserve(s.theta_m.size());
  for (const Eigen::Vector3d& raw : s.theta_m) e.wave.push_back(reading_waves(raw, model));
  // A nuisance value no sample excites is not estimated: a latch skew without
  // joint speed, or a compliance whose torque never varies (a torque-off joint
  // transmits none; a joint held at a constant torque twists by a constant
  // angle, which the zero offset dth absorbs). The cyclic error is estimated
  // under its prior, which needs the reading noise.
  MotionModel with_prior = model;
  if (!options.encoder_sigma) with_prior.cyclic_prior_rad = 0.0;
  const double prior_weight = with_prior.cyclic_prior_rad > 0.0 ? *options.encoder_sigma / with_prior.cyclic_prior_rad : 0.0;
  const std::vector<int> cols = excited_columns(with_prior, s.omega, s.tau, e.fric, e.clr, s.nb, e.flank, e.hyst.g);
  const std::vector<int> free_index = free_indices(problem.free);
  MotionFit fit = unestimated_fit();
  Problem p = problem;
  LmOptions lm = options;
  lm.compute_covariance = false;
  // The passes only lead the nuisance values; the last fit polishes.
  lm.function_tolerance = std::max(options.function_tolerance, kPassFunctionTolerance);
  std::array<double, kNuisance> nu_all = starting_nuisance(model, cols);
  unpack_nuisance(nu_all, fit);
  std::vector<LmIteration> iterations;
  Linearisation l;
  std::vector<double> w;  // the samples' weights, from the pass before's estimates (the first pass: all 1)
  // The hysteresis's threshold moves its regressor: a few more passes for its Gauss-Newton steps.
  const bool hysteresis = std::ranges::any_of(cols, [](int c) { return c >= kHysteresis; });
  const int max_passes = std::max(1, model.max_passes) + (hysteresis ? kHysteresisPasses : 0);
  for (fit.passes = 1; fit.passes <= max_passes; ++fit.passes) {
    if (fit.passes > 1) refresh_regressors(p.start, model, fit, s, e);
    p.theta_m = fully_corrected(fit, s, e);
    p.weight = w;
    fit.result = calibrate_lm(p, lm);
    // The first pass checked the samples and the free set at the start; the
    // next ones move the readings by the nuisance corrections only (the last fit checks again).
    lm.checks = fit.result.rank_deficient;
    append_iterations(iterations, fit.result.lm_iterations);
    p.start = fit.result.geometry;  // warm start for the next pass
    l = linearise(fit.result.geometry, p.theta_m, s, e, free_index, cols, w);
    if (cols.empty()) break;
    // Converged when the nuisance step moves the residuals by a negligible
    // fraction and the weights it gives move by less than 1e-3.
    const double change = nuisance_step(l, cols, prior_weight, nu_all);
    unpack_nuisance(nu_all, fit);
    std::vector<double> next = fit_weights(model, options, l.U, s.omega, e, fit);
    const double moved = weight_change(next, w);
    w = std::move(next);
    if (change < 1e-6 && moved < 1e-3) break;
  }
  fit.passes = std::min(fit.passes, max_passes);
  fit.corrected = fully_corrected(fit, s, e);
  fit.kept = std::move(kept);
  fit.tension_min_N = e.tension_min;
  for (std::size_t j = 0; j < s.theta_m.size(); ++j)
    for (int k = 0; k < 3; ++k)
      if (e.clr[j][k] != 0.0) fit.clearance_used[static_cast<std::size_t>(k)] += 1.0 / static_cast<double>(s.theta_m.size());
  p.theta_m = fit.corrected;
  p.weight = w;
  fit.weight = w;
  lm.compute_covariance = options.compute_covariance;
  lm.function_tolerance = options.function_tolerance;
  lm.checks = options.checks;
  fit.result = calibrate_lm(p, lm);
  append_iterations(iterations, fit.result.lm_iterations);
  fit.result.lm_iterations = std::move(iterations);
  fit.doubt = stated_doubt(model, options, l, s.omega);
  if (options.compute_covariance && !cols.empty() && fit.result.covariance)
    joint_covariance(l, cols, prior_weight, free_index, options, model, fit);
  else if (options.encoder_sigma)  // the chi-square without the joint covariance: at the last pass's geometry, as it
    fit.chi2 = l.r.squaredNorm() / (*options.encoder_sigma * *options.encoder_sigma);
  return fit;
}

}  // namespace

MotionFit calibrate_in_motion(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                              const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                              const MotionModel& model, const std::vector<Eigen::Vector3d>& alpha) {
  const std::vector<Eigen::Vector3d> nb = torques_before(model, tau);
  return fit_in_motion(problem, MotionSamples{problem.theta_m, omega, tau, nb, alpha}, options, model);
}

Eigen::Matrix<double, kNumParams, kNumParams> motion_crb_covariance(
    const Geometry& truth, const FreeMask& free, const std::vector<Eigen::Vector3d>& theta_m,
    const std::vector<Eigen::Vector3d>& omega, const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
    const std::vector<Eigen::Vector3d>& alpha, double sigma) {
  const std::size_t n = theta_m.size();
  if (omega.size() != n || tau.size() != n || (!alpha.empty() && alpha.size() != n))
    throw InputError(fmt::format("motion bound: {} readings but {} joint speeds, {} torques, {} accelerations", n,
                                 omega.size(), tau.size(), alpha.size()));
  const std::vector<Eigen::Vector3d> tau_t = transmitted_torques(model, omega, tau, alpha);
  std::vector<Eigen::Vector3d> clr(n, Eigen::Vector3d::Zero());
  if (model.clearance) {
    const std::vector<std::optional<PassiveForces>> forces = passive_forces(truth, theta_m, tau_t);
    clr = clearance_regressors(forces, effective_tension_min(model, forces));
  }
  const std::vector<Eigen::Vector3d> nb_all = torques_before(model, tau);
  const std::vector<Eigen::Vector3d> flank_all = flank_regressors(model, omega, tau, alpha);
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), std::size_t{0});
  const std::vector<Eigen::Vector3d> mesh = hysteresis_mesh_torques(model, omega, tau, alpha);
  const HysteresisRegressors hyst_all = hysteresis_regressors(model, mesh, all, starting_thresholds(model, mesh));
  std::vector<Eigen::Vector3d> th, w, t, c, nb, flank, hyst, hyst_slope;
  for (std::size_t j : kept_samples(model, clr, flank_all)) {
    hyst.push_back(hyst_all.g[j]);
    hyst_slope.push_back(hyst_all.slope[j]);
    if (!nb_all.empty()) nb.push_back(nb_all[j]);
    th.push_back(theta_m[j]);
    w.push_back(omega[j]);
    t.push_back(tau[j]);
    c.push_back(clr[j]);
    flank.push_back(flank_all[j]);
  }
  const std::vector<Eigen::Vector3d> fric = friction_regressors(model, w);
  const std::vector<int> cols = excited_columns(model, w, t, fric, c, nb, flank, hyst);
  const std::vector<int> free_index = free_indices(free);
  const Eigen::MatrixXd J_all = ml_jacobian(th, truth);
  const auto m = static_cast<Eigen::Index>(free_index.size() + cols.size());
  Eigen::MatrixXd J(static_cast<Eigen::Index>(th.size()), m), Jc(static_cast<Eigen::Index>(th.size()), 6);
  for (std::size_t j = 0; j < th.size(); ++j) {
    const auto row = static_cast<Eigen::Index>(j);
    for (std::size_t k = 0; k < free_index.size(); ++k) J(row, static_cast<Eigen::Index>(k)) = J_all(row, free_index[k]);
    const SampleRegressors reg{w[j], t[j], fric[j], c[j], nb.empty() ? Eigen::Vector3d::Zero() : nb[j],
                               reading_waves(th[j], model), flank[j], hyst[j], hyst_slope[j],
                               hyst_all.threshold};
    fill_nuisance_row(reading_sensitivity(J_all, j), reg, cols, row, J, Jc, static_cast<Eigen::Index>(free_index.size()));
  }
  if (model.cyclic_prior_rad > 0.0 && sigma > 0.0)
    append_cyclic_prior(cols, static_cast<Eigen::Index>(free_index.size()), sigma / model.cyclic_prior_rad, J, nullptr,
                        nullptr);
  // Column-scaled inverse (seconds, rad/N m and mm differ by orders).
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  for (Eigen::Index k = 0; k < scale.size(); ++k) scale[k] = scale[k] > 0.0 ? scale[k] : 1.0;
  const Eigen::MatrixXd Js = J * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd A = (Js.transpose() * Js).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  Eigen::MatrixXd C = sigma * sigma * A;  // of the scaled coefficients
  if (considers_cyclic(model)) add_considered(A, Js, Jc, model.cyclic_prior_rad, C);
  Eigen::Matrix<double, kNumParams, kNumParams> out = Eigen::Matrix<double, kNumParams, kNumParams>::Zero();
  for (std::size_t k = 0; k < free_index.size(); ++k)
    for (std::size_t l = 0; l < free_index.size(); ++l) {
      const auto i = static_cast<Eigen::Index>(k), j = static_cast<Eigen::Index>(l);
      out(free_index[k], free_index[l]) = C(i, j) / (scale[i] * scale[j]);
    }
  return out;
}

std::array<double, kNumParams> motion_crb(const Geometry& truth, const FreeMask& free,
                                          const std::vector<Eigen::Vector3d>& theta_m,
                                          const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
                                          const std::vector<Eigen::Vector3d>& alpha, double sigma) {
  const Eigen::Matrix<double, kNumParams, kNumParams> C =
      motion_crb_covariance(truth, free, theta_m, omega, tau, model, alpha, sigma);
  std::array<double, kNumParams> out;
  out.fill(std::numeric_limits<double>::quiet_NaN());
  for (int k : free_indices(free)) out[static_cast<std::size_t>(k)] = std::sqrt(C(k, k));
  return out;
}

std::vector<double> hysteresis_state(const std::vector<double>& tau, double threshold_Nm) {
  std::vector<double> g(tau.size(), 0.0);
  for (std::size_t k = 1; k < tau.size(); ++k) {
    const double change = tau[k] - tau[k - 1];
    if (threshold_Nm > 0.0) g[k] = std::clamp(g[k - 1] + change / (2.0 * threshold_Nm), -1.0, 1.0);
    else g[k] = change > 0.0 ? 1.0 : change < 0.0 ? -1.0 : g[k - 1];
  }
  return g;
}

double starting_hysteresis_threshold(const MotionModel& model) {
  return model.hysteresis_start_rad / model.hysteresis_compliance_rad_per_Nm;
}

double largest_hysteresis_threshold(double torque_range_Nm) { return 0.25 * torque_range_Nm; }

bool clearance_detected(const MotionFit& fit, double k) {
  for (std::size_t i = 0; i < 3; ++i)
    if (std::isfinite(fit.noise_sigma.clearance[i]) && std::abs(fit.clearance[i]) >= k * fit.noise_sigma.clearance[i])
      return true;
  return false;
}

bool torque_before_detected(const MotionFit& fit, double k) {
  for (std::size_t i = 0; i < 3; ++i)
    if (std::isfinite(fit.noise_sigma.torque_before[i]) &&
        std::abs(fit.torque_before[i]) >= k * fit.noise_sigma.torque_before[i])
      return true;
  return false;
}

namespace {

// A candidate effect of left_out_effects: its name and its nuisance columns.
struct Candidate {
  std::string name;
  std::vector<int> cols;
};

// The effects model leaves out, each with its columns (nuisance_columns' slots).
std::vector<Candidate> left_out_candidates(const MotionModel& model) {
  std::vector<Candidate> c;
  if (!model.skew) c.push_back({"the encoders' latch skew", {kSkew, kSkew + 1}});
  if (!model.compliance) c.push_back({"transmission compliance", {kCompliance, kCompliance + 1, kCompliance + 2}});
  if (!(model.compliance && model.friction)) c.push_back({"the drives' friction twist", {kFriction, kFriction + 1, kFriction + 2}});
  if (!model.clearance) c.push_back({"joint clearance", {kClearance, kClearance + 1, kClearance + 2}});
  if (!model.estimate_cyclic)
    c.push_back({"an error once per joint revolution", {kFirstCyclic, kFirstCyclic + 1, kFirstCyclic + 2, kFirstCyclic + 3,
                                                         kFirstCyclic + 4, kFirstCyclic + 5}});
  for (int i = 0; model.encoder_on_motor && i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!model.backlash[k]) c.push_back({fmt::format("backlash of joint {}", i + 1), {kBacklash + i}});
    if (!model.motor_harmonic1[k])
      c.push_back({fmt::format("an error once per motor revolution of joint {}", i + 1), {kHarmonic + 6 + i, kHarmonic + 9 + i}});
    if (!model.motor_harmonic2[k])
      c.push_back({fmt::format("an error twice per motor revolution of joint {}", i + 1), {kHarmonic + 12 + i, kHarmonic + 15 + i}});
    if (model.cogging_periods > 0.0 && !model.cogging[k])
      c.push_back({fmt::format("the cogging of motor {}", i + 1), {kHarmonic + 18 + i, kHarmonic + 21 + i}});
  }
  return c;
}

// model with every candidate of left_out_candidates in it (the regressors' model).
MotionModel with_every_candidate(MotionModel all) {
  all.skew = all.compliance = all.friction = all.clearance = true;
  if (!(all.load.friction_speed_rad_s > 0.0)) all.load.friction_speed_rad_s = 0.1;
  all.estimate_cyclic = true;
  if (!(all.cyclic_prior_rad > 0.0)) all.cyclic_prior_rad = 1.0;  // the columns only: no prior rows are used
  all.backlash = all.motor_harmonic1 = all.motor_harmonic2 = {true, true, true};
  if (all.cogging_periods > 0.0) all.cogging = {true, true, true};
  all.drop_uncertain = false;
  return all;
}

// The chi-square drop (in units of sigma^2) of residuals rp when the columns
// G join the columns with orthonormal basis Qo (rp: the residuals with those
// columns projected out): |P rp|^2 for P the projection on G with Qo
// projected out; rank: of G so projected.
double score_chi2(const Eigen::MatrixXd& Qo, const Eigen::MatrixXd& G, const Eigen::VectorXd& rp, int& rank) {
  const Eigen::MatrixXd Gp = G - Qo * (Qo.transpose() * G);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> g(Gp);
  g.setThreshold(1e-6);
  rank = static_cast<int>(g.rank());
  if (rank == 0) return 0.0;
  const Eigen::MatrixXd Go = (g.householderQ() * Eigen::MatrixXd::Identity(Gp.rows(), Gp.cols())).leftCols(rank);
  return (Go.transpose() * rp).squaredNorm();
}

// The candidate of left_out_effects beside left_out_candidates' (its columns: friction_dynamics_columns).
constexpr const char* kFrictionDynamics =
    "the drives' friction dynamics (a friction that is no function of the speed alone: it leads, lags or sticks)";

// The columns of the drives' friction dynamics, a candidate of
// left_out_effects: a friction that acts on the speed kappa_i ahead (kappa_i
// < 0: behind, as presliding makes it) twists by c_i F_i tanh((omega_i +
// kappa_i alpha_i) / v), whose change to first order is c_i F_i kappa_i
// alpha_i sech^2(omega_i / v) / v: per joint the column u_i alpha_i
// sech^2(omega_i / v) / v (u_i the sample's reading sensitivity, a row of
// the linearisation's U), value c_i F_i kappa_i.
Eigen::MatrixXd friction_dynamics_columns(const Eigen::MatrixXd& U, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& alpha, double v) {
  Eigen::MatrixXd G(U.rows(), 3);
  for (Eigen::Index j = 0; j < U.rows(); ++j)
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(j);
      const double c = std::cosh(omega[k][i] / v);
      G(j, i) = U(j, i) * alpha[k][i] / (v * c * c);
    }
  return G;
}

}  // namespace

std::vector<LeftOutEffect> left_out_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                            const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
                                            const MotionFit& fit, double sigma,
                                            const std::vector<Eigen::Vector3d>& alpha) {
  std::vector<LeftOutEffect> out;
  if (!(sigma > 0.0) || fit.kept.empty() || fit.corrected.size() != fit.kept.size()) return out;
  const MotionModel all = with_every_candidate(model);
  const std::vector<Eigen::Vector3d> nb_all = torques_before(model, tau);
  const EffectRegressors e_all =
      effect_regressors(fit.result.geometry, MotionSamples{problem.theta_m, omega, tau, nb_all, alpha}, all);
  EffectRegressors e = kept_regressors(e_all, fit.kept);
  std::vector<Eigen::Vector3d> th, w, t, nb, no_alpha;
  for (std::size_t j : fit.kept) {
    th.push_back(problem.theta_m[j]), w.push_back(omega[j]), t.push_back(tau[j]);
    if (!nb_all.empty()) nb.push_back(nb_all[j]);
    e.wave.push_back(reading_waves(problem.theta_m[j], model));
  }
  const MotionSamples s{th, w, t, nb, no_alpha};
  const std::vector<int> own = excited_columns(model, s.omega, s.tau, e.fric, e.clr, s.nb, e.flank, e.hyst.g);
  const std::vector<int> candidates = excited_columns(all, s.omega, s.tau, e.fric, e.clr, s.nb, e.flank, e.hyst.g);
  std::vector<int> cols = own;
  for (int c : candidates)
    if (std::ranges::find(own, c) == own.end()) cols.push_back(c);
  const Linearisation l = linearise(fit.result.geometry, fit.corrected, s, e, free_indices(problem.free), cols,
                                    fit.weight.size() == fit.kept.size() ? fit.weight : std::vector<double>{});
  const auto n_own = static_cast<Eigen::Index>(own.size());
  Eigen::MatrixXd Q(l.r.size(), l.Jg.cols() + n_own);
  Q << l.Jg, l.Jn.leftCols(n_own);
  // The fit's own columns, orthonormal, and the residuals with them projected out: the same for every candidate.
  const Eigen::MatrixXd Qo =
      Eigen::HouseholderQR<Eigen::MatrixXd>(Q).householderQ() * Eigen::MatrixXd::Identity(Q.rows(), Q.cols());
  const Eigen::VectorXd rp = l.r / sigma - Qo * (Qo.transpose() * (l.r / sigma));
  for (const Candidate& c : left_out_candidates(model)) {
    std::vector<Eigen::Index> at;
    for (int col : c.cols)
      if (const auto it = std::ranges::find(cols, col); it != cols.end() && std::ranges::find(own, col) == own.end())
        at.push_back(static_cast<Eigen::Index>(it - cols.begin()));
    if (at.empty()) continue;
    Eigen::MatrixXd G(l.r.size(), static_cast<Eigen::Index>(at.size()));
    for (std::size_t k = 0; k < at.size(); ++k) G.col(static_cast<Eigen::Index>(k)) = l.Jn.col(at[k]);
    int rank = 0;
    const double drop = score_chi2(Qo, G, rp, rank);
    if (rank > 0 && chi2_survival(rank, drop) < 1e-3) out.push_back({c.name, drop, rank});
  }
  const double v = model.load.friction_speed_rad_s;
  if (model.compliance && model.friction && v > 0.0 && !alpha.empty()) {
    std::vector<Eigen::Vector3d> a;
    for (std::size_t j : fit.kept) a.push_back(alpha[j]);
    int rank = 0;
    const double drop = score_chi2(Qo, l.w.asDiagonal() * friction_dynamics_columns(l.U, w, a, v), rp, rank);
    if (rank > 0 && chi2_survival(rank, drop) < 1e-3)
      out.push_back({kFrictionDynamics, drop, rank});
  }
  std::ranges::sort(out, std::greater<>{}, &LeftOutEffect::chi2_drop);
  return out;
}

}  // namespace gpm::calib
