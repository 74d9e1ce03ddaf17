#include "calib/lm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <ceres/ceres.h>
#include <Eigen/Dense>
#include <fmt/format.h>

#include "calib/identifiability.hpp"
#include "calib/kmrmse.hpp"
#include "calib/parameterization.hpp"
#include "calib/residuals.hpp"
#include "calib/sample_check.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

using Mat15 = Eigen::Matrix<double, kNumParams, kNumParams>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Residuals (stacked) and their Jacobian w.r.t. all 15 solver slots at x.
struct Evaluation {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  bool ok = true;
};

Evaluation evaluate(const std::vector<std::unique_ptr<ceres::CostFunction>>& f, const ParamVector& x,
                    int rows, bool with_jacobian) {
  Evaluation e;
  const auto m = static_cast<Eigen::Index>(f.size()) * rows;
  e.r.resize(m);
  if (with_jacobian) e.J.resize(m, kNumParams);
  Eigen::Matrix<double, Eigen::Dynamic, kNumParams, Eigen::RowMajor> Jj(rows, kNumParams);
  const double* params[] = {x.data()};
  for (size_t j = 0; j < f.size(); ++j) {
    double* jac[] = {Jj.data()};
    double* r = e.r.data() + static_cast<Eigen::Index>(j) * rows;
    if (!f[j]->Evaluate(params, r, with_jacobian ? jac : nullptr)) {
      e.ok = false;
      return e;
    }
    if (with_jacobian) e.J.middleRows(static_cast<Eigen::Index>(j) * rows, rows) = Jj;
  }
  return e;
}

// All samples' residuals as one Ceres residual block over the free
// parameters only (rows stacked in sample order, fixed slots taken from
// *full): the same residuals and Jacobian columns as one block per sample on
// all 15 slots with the fixed ones held constant, without Ceres' per-block
// and manifold bookkeeping (most of an LM solve otherwise).
class FreeStackedResidual final : public ceres::CostFunction {
 public:
  FreeStackedResidual(const std::vector<std::unique_ptr<ceres::CostFunction>>& f, int rows,
                      const std::vector<int>& free_index, const ParamVector& full)
      : f_(f), rows_(rows), idx_(free_index), full_(full) {
    set_num_residuals(static_cast<int>(f.size()) * rows);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(free_index.size()));
  }
  bool Evaluate(double const* const* xf, double* r, double** jac) const override {
    ParamVector x = full_;
    const size_t p = idx_.size();
    for (size_t k = 0; k < p; ++k) x[static_cast<size_t>(idx_[k])] = xf[0][k];
    const double* params[] = {x.data()};
    double Jj[6 * kNumParams];
    double* jj[] = {Jj};
    const bool with_jacobian = jac && jac[0];
    for (size_t j = 0; j < f_.size(); ++j) {
      const size_t row = j * static_cast<size_t>(rows_);
      if (!f_[j]->Evaluate(params, r + row, with_jacobian ? jj : nullptr)) return false;
      if (!with_jacobian) continue;
      for (int q = 0; q < rows_; ++q)
        for (size_t k = 0; k < p; ++k)
          jac[0][(row + static_cast<size_t>(q)) * p + k] = Jj[q * kNumParams + idx_[k]];
    }
    return true;
  }

 private:
  const std::vector<std::unique_ptr<ceres::CostFunction>>& f_;
  int rows_;
  std::vector<int> idx_;
  const ParamVector& full_;
};

// The solver slots that problem.free leaves free, in slot order.
std::vector<int> free_slots(const FreeMask& free) {
  std::vector<int> idx;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) idx.push_back(i);
  return idx;
}

// Minimum-norm Levenberg-Marquardt for a rank-deficient free set: each step
// is the damped pseudo-inverse step restricted to the `rank` largest singular
// directions of the column-scaled Jacobian, so it never moves along the
// unobservable family and ends at the member nearest the start (first order).
void truncated_svd_lm(const std::vector<std::unique_ptr<ceres::CostFunction>>& f, int rows,
                      const FreeMask& free, int rank, int max_iterations, ParamVector& x,
                      Result& res) {
  const std::vector<int> idx = free_slots(free);
  const auto p = static_cast<Eigen::Index>(idx.size());
  Evaluation e = evaluate(f, x, rows, true);
  res.evaluations = 1;
  if (!e.ok) throw InputError("start geometry: a sample has collinear elbows (no forward kinematics)");
  Eigen::VectorXd D(p);  // column scales, frozen at the start
  for (Eigen::Index k = 0; k < p; ++k) D[k] = std::max(e.J.col(idx[static_cast<size_t>(k)]).norm(), 1e-300);
  double cost = e.r.squaredNorm();
  res.lm_iterations.push_back({0, paper_cost(res.cost, cost), 0.0, true});
  double lambda = -1.0;
  res.converged = false;
  long it = 0;
  for (; it < max_iterations; ++it) {
    Eigen::MatrixXd Js(e.J.rows(), p);
    for (Eigen::Index k = 0; k < p; ++k) Js.col(k) = e.J.col(idx[static_cast<size_t>(k)]) / D[k];
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    if (lambda < 0.0) lambda = 1e-6 * s[0] * s[0];
    const Eigen::VectorXd Utr = svd.matrixU().transpose() * e.r;
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      Eigen::VectorXd step_s = Eigen::VectorXd::Zero(p);
      for (int k = 0; k < rank; ++k) step_s -= svd.matrixV().col(k) * (s[k] / (s[k] * s[k] + lambda) * Utr[k]);
      ParamVector xt = x;
      for (Eigen::Index k = 0; k < p; ++k) xt[static_cast<size_t>(idx[static_cast<size_t>(k)])] += step_s[k] / D[k];
      const Evaluation et = evaluate(f, xt, rows, false);
      ++res.evaluations;
      const double cost_t = et.ok ? et.r.squaredNorm() : std::numeric_limits<double>::infinity();
      double step_norm = 0.0;
      for (Eigen::Index k = 0; k < p; ++k) step_norm += std::pow(step_s[k] / D[k], 2);
      res.lm_iterations.push_back({static_cast<int>(res.lm_iterations.size()), paper_cost(res.cost, cost_t),
                                   std::sqrt(step_norm), cost_t < cost});
      if (cost_t < cost) {
        const double drop = (cost - cost_t) / std::max(cost, 1e-300);
        double xs = 0.0;
        for (Eigen::Index k = 0; k < p; ++k) xs += std::pow(x[static_cast<size_t>(idx[static_cast<size_t>(k)])] * D[k], 2);
        x = xt;
        cost = cost_t;
        lambda = std::max(lambda / 3.0, 1e-20 * s[0] * s[0]);
        accepted = true;
        if (drop < 1e-14 || step_s.norm() < 1e-13 * (std::sqrt(xs) + 1e-13) || cost == 0.0) {
          res.converged = true;
        }
      } else {
        lambda *= 4.0;
      }
    }
    if (!accepted) {  // no decrease possible along the observable directions: at the floor
      res.converged = true;
      break;
    }
    if (res.converged) break;
    e = evaluate(f, x, rows, true);
    ++res.evaluations;
  }
  res.iterations = it + 1;
}

// Gauss-Newton polish after Levenberg-Marquardt. Near the optimum of noisy
// data the cost changes of the last steps fall below the rounding of the cost
// itself (1e-12 to 3e-12 relative here), so the trust region rejects good
// steps and stops up to a few 1e-6 sigma short. The Gauss-Newton step
// -(J'J)^-1 J'r needs no cost comparison (the gradient J'r is accurate far
// below that); with residuals left it converges linearly (each step about
// 1/20 of the last here), so it runs while its steps keep shrinking by at
// least half (at most 10), and stops at a cost rise beyond rounding (1e-9
// relative: a step leaving the basin). Returns the evaluations used.
long polish_gauss_newton(const std::vector<std::unique_ptr<ceres::CostFunction>>& f, int rows,
                         const std::vector<int>& free_index, ParamVector& x) {
  const auto p = static_cast<Eigen::Index>(free_index.size());
  Evaluation e = evaluate(f, x, rows, true);
  long evaluations = 1;
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 10 && e.ok; ++it) {
    Eigen::MatrixXd Jf(e.J.rows(), p);
    Eigen::VectorXd scale(p);
    for (Eigen::Index k = 0; k < p; ++k) {
      Jf.col(k) = e.J.col(free_index[static_cast<size_t>(k)]);
      scale[k] = std::max(Jf.col(k).norm(), 1e-300);
      Jf.col(k) /= scale[k];
    }
    const Eigen::VectorXd step_s = Jf.colPivHouseholderQr().solve(-e.r);
    const double step = step_s.norm();
    if (!std::isfinite(step) || !(step < 0.5 * last_step)) break;
    ParamVector xt = x;
    for (Eigen::Index k = 0; k < p; ++k) xt[static_cast<size_t>(free_index[static_cast<size_t>(k)])] += step_s[k] / scale[k];
    Evaluation et = evaluate(f, xt, rows, true);
    ++evaluations;
    if (!et.ok || !(et.r.squaredNorm() <= e.r.squaredNorm() * (1.0 + 1e-9) + 1e-300)) break;
    x = xt;
    e = std::move(et);
    last_step = step;
  }
  return evaluations;
}

// Throws InputError for samples, a free set, an iteration budget or a noise that LM cannot use.
void check_lm_inputs(const Problem& problem, const LmOptions& opt) {
  check_samples(problem);
  if (!problem.weight.empty() && problem.weight.size() != problem.theta_m.size())
    throw InputError(fmt::format("calibration: {} sample weights for {} samples", problem.weight.size(),
                                 problem.theta_m.size()));
  if (std::ranges::any_of(problem.weight, [](double w) { return !(w >= 0.0) || !std::isfinite(w); }))
    throw InputError("calibration: a sample weight is negative or not finite (valid: finite, >= 0)");
  check_free_set(problem.free, opt.cost);
  if (opt.max_iterations < 1) throw InputError("--budget: LM needs at least one iteration");
  if (opt.encoder_sigma) check_bound(*opt.encoder_sigma, limits::kEncoderSigma, "--sigma");
}

// The identifiability of problem.free at the start (rank and condition into res); refuses a
// rank-deficient set unless allowed, and notes rank deficiency or poor conditioning.
Identifiability note_identifiability(const Problem& problem, const LmOptions& opt, Result& res) {
  const int p = static_cast<int>(problem.free.count());
  Identifiability id = analyse_identifiability(problem.theta_m, problem.start, problem.free);
  res.rank = id.rank;
  res.condition_number = id.condition_number;
  if (id.rank < p) {
    if (!opt.allow_rank_deficient) require_identifiable(id, problem.free);
    res.rank_deficient = true;
    res.notes.push_back(fmt::format(
        "rank-deficient free set (rank {} of {}): {}; solved anyway with a minimum-norm "
        "(truncated-SVD) Levenberg-Marquardt step, so the estimate is the member of that family "
        "nearest the start, not necessarily the true geometry; {}",
        id.rank, p, id.description, id.advice));
  } else if (id.condition_number > kPoorConditioning) {
    res.notes.push_back(fmt::format(
        "poorly exciting samples: condition number {:.3g} of the scaled Jacobian exceeds {:.0e}; "
        "the estimates are very sensitive to noise (spread the samples over the workspace)",
        id.condition_number, kPoorConditioning));
  }
  return id;
}

// Ceres' problem options: the residual blocks stay owned by the caller.
ceres::Problem::Options borrowed_blocks() {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return po;
}

// A sample's residuals times its weight w (Problem::weight): w r(x), w dr/dx.
class WeightedSample final : public ceres::CostFunction {
 public:
  WeightedSample(std::unique_ptr<ceres::CostFunction> f, double w) : f_(std::move(f)), w_(w) {
    set_num_residuals(f_->num_residuals());
    *mutable_parameter_block_sizes() = f_->parameter_block_sizes();
  }
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    if (!f_->Evaluate(x, r, jac)) return false;
    const int rows = num_residuals();
    for (int q = 0; q < rows; ++q) r[q] *= w_;
    if (jac && jac[0])
      for (int k = 0; k < rows * parameter_block_sizes()[0]; ++k) jac[0][k] *= w_;
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> f_;
  double w_;
};

// One residual function per sample of problem (autodiff or analytic per opt), weighted by problem.weight.
std::vector<std::unique_ptr<ceres::CostFunction>> sample_functions(const Problem& problem, const LmOptions& opt) {
  std::vector<std::unique_ptr<ceres::CostFunction>> functions;
  functions.reserve(problem.theta_m.size());
  for (std::size_t j = 0; j < problem.theta_m.size(); ++j) {
    const Eigen::Vector3d& t = problem.theta_m[j];
    std::unique_ptr<ceres::CostFunction> f(opt.autodiff ? make_autodiff_residual(opt.cost, t) : make_residual(opt.cost, t));
    if (!problem.weight.empty()) f = std::make_unique<WeightedSample>(std::move(f), problem.weight[j]);
    functions.push_back(std::move(f));
  }
  return functions;
}

// One LM solve's state: the samples' residual functions, the solver vector x (all 15 slots),
// its free values xf and the Ceres problem over xf (one stacked block, robust when
// opt.loss is set), which refers to the other members: neither copied nor moved.
struct LmSolve {
  LmSolve(const Problem& problem, const LmOptions& opt)
      : rows(residual_rows(opt.cost)),
        functions(sample_functions(problem, opt)),
        x(to_solver(problem.start, opt.cost)),
        free_index(free_slots(problem.free)),
        stacked(functions, rows, free_index, x),
        cp(borrowed_blocks()) {
    for (int i : free_index) xf.push_back(x[static_cast<size_t>(i)]);
    rho = make_loss_function(opt.loss);
    if (rho) robust = make_robust_residual(&stacked, rows, rho.get());
    cp.AddResidualBlock(robust ? robust.get() : &stacked, nullptr, xf.data());
  }
  LmSolve(const LmSolve&) = delete;
  LmSolve& operator=(const LmSolve&) = delete;

  const int rows;
  std::vector<std::unique_ptr<ceres::CostFunction>> functions;
  ParamVector x;
  const std::vector<int> free_index;
  std::vector<double> xf;
  FreeStackedResidual stacked;
  std::unique_ptr<ceres::LossFunction> rho;
  std::unique_ptr<ceres::CostFunction> robust;
  ceres::Problem cp;
};

// Ceres' Levenberg-Marquardt settings for budget max_iterations.
ceres::Solver::Options solver_options(int max_iterations, double function_tolerance) {
  ceres::Solver::Options so;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  // Start nearly undamped: with Jacobi scaling the damping is 1 / radius
  // against a normal matrix of unit diagonal whose smallest eigenvalue is
  // 1 / cond^2 (about 2e-6 for 50 samples, cond ~ 700), so Ceres' default
  // 1e4 damps the weakest directions for several iterations (J1: 10
  // iterations instead of 5). Failed steps still raise the damping.
  so.initial_trust_region_radius = 1e8;
  so.max_num_iterations = max_iterations;
  so.function_tolerance = function_tolerance;
  so.gradient_tolerance = 1e-16;
  so.parameter_tolerance = 1e-14;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  return so;
}

// Solves s with Ceres LM (and the Gauss-Newton polish where steps were
// rejected under the plain loss); s.x and the iterations, evaluations and
// convergence of res follow. Throws Error when the cost cannot be evaluated.
void solve_ceres(LmSolve& s, const LmOptions& opt, Result& res) {
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(opt.max_iterations, opt.function_tolerance), &s.cp, &summary);
  // A cost that cannot be evaluated (NaN or infinite: a loss scale or noise
  // far outside the residuals, issue 36.1) is a failed calibration, said in
  // one line, not a result.
  if (summary.termination_type == ceres::FAILURE || !std::isfinite(summary.final_cost))
    throw Error(fmt::format("the calibration failed: {} (cost function {}, loss {})", summary.message,
                            cost_name(opt.cost), loss_name(opt.loss)));
  for (const ceres::IterationSummary& it : summary.iterations)  // Ceres' cost is half the sum of squares
    res.lm_iterations.push_back({it.iteration, paper_cost(opt.cost, 2.0 * it.cost), it.step_norm,
                                 it.step_is_successful || it.iteration == 0});
  for (size_t k = 0; k < s.free_index.size(); ++k) s.x[static_cast<size_t>(s.free_index[k])] = s.xf[k];
  res.iterations = static_cast<long>(summary.num_successful_steps + summary.num_unsuccessful_steps);
  // Each Jacobian evaluation also evaluates the residuals: count both kinds.
  res.evaluations = summary.num_residual_evaluations + summary.num_jacobian_evaluations;
  res.converged = summary.termination_type == ceres::CONVERGENCE;
  // Rejected steps: the cost may have reached its rounding floor short of the
  // optimum. The polish solves the plain least-squares problem, so it is for
  // the plain loss only (a robust loss has its own optimum).
  if (res.converged && !s.rho && summary.num_unsuccessful_steps > 0)
    res.evaluations += polish_gauss_newton(s.functions, s.rows, s.free_index, s.x);
  if (!res.converged) res.notes.push_back(fmt::format("Levenberg-Marquardt did not converge: {}", summary.message));
}

// The residuals (and, with_jacobian, the Jacobian) at the solution as the
// solved problem weighs them: under a robust loss each sample's rows and
// Jacobian rows scaled by its factor W_j (calib/robust_loss.hpp), kept in W.
struct Weighted {
  Evaluation e;
  std::vector<Eigen::MatrixXd> W;
};

// The solution's residuals weighted as in the solve (Weighted); the paper's cost of the
// unweighted residuals into res.final_cost. Throws Error for a non-finite geometry or cost.
Weighted evaluate_solution(const LmSolve& s, const LmOptions& opt, bool with_jacobian, Result& res) {
  Weighted w{evaluate(s.functions, s.x, s.rows, with_jacobian), {}};
  Evaluation& fin = w.e;
  res.final_cost = paper_cost(opt.cost, fin.ok ? fin.r.squaredNorm() : kNaN);
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!std::all_of(res.geometry.values.begin(), res.geometry.values.end(), finite) || !std::isfinite(res.final_cost))
    throw Error(fmt::format("the calibration failed: the {} cost is not a finite number at the solution (loss {})",
                            cost_name(opt.cost), loss_name(opt.loss)));
  for (size_t j = 0; s.rho && fin.ok && j < s.functions.size(); ++j) {
    const auto g = static_cast<Eigen::Index>(j) * s.rows;
    w.W.push_back(robust_factor(*s.rho, fin.r.segment(g, s.rows)));
    if (fin.J.rows() > 0) fin.J.middleRows(g, s.rows) = w.W.back() * fin.J.middleRows(g, s.rows);
    fin.r.segment(g, s.rows) = robust_residual(*s.rho, fin.r.segment(g, s.rows));
  }
  return w;
}

// C0 = (J'J)^-1 of the free values from ceres::Covariance at s.x, embedded in
// the 15 slots (zero rows and columns for fixed ones); false when singular.
bool unit_covariance(LmSolve& s, Mat15& C0) {
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.num_threads = 1;
  ceres::Covariance cov(co);
  for (size_t k = 0; k < s.free_index.size(); ++k) s.xf[k] = s.x[static_cast<size_t>(s.free_index[k])];
  const std::vector<std::pair<const double*, const double*>> blocks = {{s.xf.data(), s.xf.data()}};
  const auto nf = static_cast<Eigen::Index>(s.free_index.size());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Cf(nf, nf);
  C0 = Mat15::Zero();
  if (!cov.Compute(blocks, &s.cp) || !cov.GetCovarianceBlock(s.xf.data(), s.xf.data(), Cf.data())) return false;
  for (Eigen::Index a = 0; a < nf; ++a)
    for (Eigen::Index b = 0; b < nf; ++b) C0(s.free_index[static_cast<size_t>(a)], s.free_index[static_cast<size_t>(b)]) = Cf(a, b);
  return true;
}

// R_j = d r_j / d theta_m of one sample's residuals at x (central differences, step 1e-6 rad).
Eigen::MatrixXd reading_jacobian(Cost cost, const Eigen::Vector3d& theta_m, const ParamVector& x, int rows) {
  const double h = 1e-6;
  Eigen::MatrixXd R(rows, 3);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d tp = theta_m, tm = theta_m;
    tp[k] += h;
    tm[k] -= h;
    std::unique_ptr<ceres::CostFunction> fp(make_residual(cost, tp)), fm(make_residual(cost, tm));
    Eigen::VectorXd rp(rows), rm(rows);
    const double* params[] = {x.data()};
    fp->Evaluate(params, rp.data(), nullptr);
    fm->Evaluate(params, rm.data(), nullptr);
    R.col(k) = (rp - rm) / (2.0 * h);
  }
  return R;
}

// The sandwich's middle sum_j J_j' S_j J_j with the residuals' covariance
// under reading noise sigma, S_j = sigma^2 R_j R_j' (W_j R_j under a robust loss).
Mat15 reading_noise_meat(const Problem& problem, const LmSolve& s, const Weighted& fin, Cost cost, double sigma) {
  const double s2 = sigma * sigma;
  Mat15 M = Mat15::Zero();
  for (size_t j = 0; j < problem.theta_m.size(); ++j) {
    Eigen::MatrixXd R = reading_jacobian(cost, problem.theta_m[j], s.x, s.rows);
    if (!problem.weight.empty()) R *= problem.weight[j];
    if (!fin.W.empty()) R = fin.W[j] * R;
    const auto Jj = fin.e.J.middleRows(static_cast<Eigen::Index>(j) * s.rows, s.rows);
    const Eigen::MatrixXd JR = Jj.transpose() * R;
    M += s2 * JR * JR.transpose();
  }
  return M;
}

// The 1-sigma and covariance of the estimated parameters (res.sigma,
// res.covariance) from C0 = (J'J)^-1: the sandwich C0 M C0 when the reading
// noise is given, else C0 scaled by the residuals' variance (a note when
// nothing is left to estimate it from, or when J is singular).
void estimate_covariance(const Problem& problem, const LmOptions& opt, LmSolve& s, const Weighted& fin,
                         Result& res) {
  Mat15 C0;
  if (!unit_covariance(s, C0)) {
    res.notes.push_back("no 1-sigma: the Jacobian at the solution is numerically singular");
    return;
  }
  const int n = static_cast<int>(problem.theta_m.size());
  const int p = static_cast<int>(problem.free.count());
  Mat15 C;
  if (opt.encoder_sigma) {
    C = C0 * reading_noise_meat(problem, s, fin, opt.cost, *opt.encoder_sigma) * C0;
  } else if (n > p) {
    C = (fin.e.r.squaredNorm() / static_cast<double>(n - p)) * C0;
  } else {
    C.setConstant(kNaN);
    res.notes.push_back("no 1-sigma: as many samples as free parameters leave no residual to "
                        "estimate the noise from (give --sigma or more samples)");
  }
  const Mat15 T = geometry_jacobian(s.x, opt.cost);
  const Mat15 Cg = T * C * T.transpose();
  res.covariance = Cg;
  for (int i = 0; i < kNumParams; ++i)
    if (problem.free.test(static_cast<size_t>(i))) res.sigma[static_cast<size_t>(i)] = std::sqrt(std::max(Cg(i, i), 0.0));
}

}  // namespace

Result calibrate_lm(const Problem& problem, const LmOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (opt.checks) check_lm_inputs(problem, opt);
  Result res;
  res.method = "lm";
  res.cost = opt.cost;
  res.free = problem.free;
  res.sigma.fill(kNaN);
  Identifiability id;
  if (opt.checks) id = note_identifiability(problem, opt, res);

  LmSolve s(problem, opt);
  if (res.rank_deficient)
    truncated_svd_lm(s.functions, s.rows, problem.free, id.rank, opt.max_iterations, s.x, res);
  else
    solve_ceres(s, opt, res);
  res.geometry = from_solver(s.x, opt.cost);
  const bool with_covariance = opt.compute_covariance && !res.rank_deficient;
  const Weighted fin = evaluate_solution(s, opt, with_covariance, res);
  if (with_covariance && fin.e.ok) estimate_covariance(problem, opt, s, fin, res);

  if (opt.checks && problem.true_xy.size() == problem.theta_m.size())
    res.kmrmse_mm = kmrmse(res.geometry, problem.theta_m, problem.true_xy);
  res.history.emplace_back(res.evaluations, res.final_cost);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace gpm::calib
