#include "calib/montecarlo.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "calib/crb.hpp"
#include "calib/lm.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib {

MonteCarloOptions default_montecarlo_options() {
  MonteCarloOptions o;
  o.actual = table5_actual();
  o.start = Geometry::gpm2002_nominal();
  o.free = default_free_mask();
  for (int i = 0; i < kNumParams; ++i)
    if (!o.free.test(static_cast<size_t>(i))) o.start[i] = o.actual[i];
  return o;
}

std::vector<MonteCarloRow> run_montecarlo(const MonteCarloOptions& o) {
  Robot actual;
  actual.geometry = o.actual;
  const auto poses = disc_poses(actual, o.samples, actual.home, o.radius_mm, o.seed);
  const std::vector<Eigen::Vector3d> clean = samples_at(actual, poses).theta_m;
  const Eigen::MatrixXd fisher = fisher_information(o.actual, o.free, clean, o.sigma);
  const auto bound = crb_sigma(o.actual, o.free, clean, o.sigma);
  std::vector<int> idx;
  for (int i = 0; i < kNumParams; ++i)
    if (o.free.test(static_cast<size_t>(i))) idx.push_back(i);
  const auto p = static_cast<Eigen::Index>(idx.size());

  std::vector<MonteCarloRow> rows;
  for (Cost c : o.costs) {
    MonteCarloRow row;
    row.cost = c;
    row.bound = bound;
    std::array<double, kNumParams> sum_sq{}, sum_sigma{};
    double sum_mahalanobis = 0.0;
    int ok = 0;
    for (int t = 0; t < o.trials; ++t) {
      // Same noise in every cost's trial t: a paired comparison.
      const Samples s = samples_at(actual, poses, o.sigma, o.seed * 1000003ULL + static_cast<std::uint64_t>(t));
      LmOptions lm;
      lm.cost = c;
      lm.encoder_sigma = o.sigma;
      const Result r = calibrate_lm(Problem{s.theta_m, o.start, o.free}, lm);
      if (!r.converged) {
        ++row.failures;
        continue;
      }
      ++ok;
      Eigen::VectorXd e(p);
      for (Eigen::Index k = 0; k < p; ++k) {
        const auto i = static_cast<size_t>(idx[static_cast<size_t>(k)]);
        e[k] = r.geometry.values[i] - o.actual.values[i];
        sum_sq[i] += e[k] * e[k];
        sum_sigma[i] += r.sigma[i];
      }
      sum_mahalanobis += e.dot(fisher * e) / static_cast<double>(p);
    }
    for (int i = 0; i < kNumParams; ++i) {
      const auto u = static_cast<size_t>(i);
      if (!o.free.test(u) || ok == 0) {
        row.rms_error[u] = row.ratio[u] = row.mean_reported_sigma[u] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      row.rms_error[u] = std::sqrt(sum_sq[u] / ok);
      row.ratio[u] = row.rms_error[u] / bound[u];
      row.mean_reported_sigma[u] = sum_sigma[u] / ok;
      row.max_ratio = std::max(row.max_ratio, row.ratio[u]);
      row.rms_ratio += row.ratio[u] * row.ratio[u] / static_cast<double>(p);
    }
    row.rms_ratio = std::sqrt(row.rms_ratio);
    row.normalised_ratio = ok ? std::sqrt(sum_mahalanobis / ok) : std::numeric_limits<double>::quiet_NaN();
    rows.push_back(row);
  }
  return rows;
}

}  // namespace gpm::calib
