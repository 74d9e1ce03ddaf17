// Times one whole LM calibration (calib/lm.hpp: identifiability, Ceres LM;
// covariance off, as scipy computes none) of a samples CSV, many repetitions,
// and prints the median time and the largest error against the true geometry.
//   bench_calib_lm SAMPLES.csv REPETITIONS COST [cov] [autodiff]
// ("cov" also computes the 1-sigma, as gpm calibrate does; "autodiff" uses
// Ceres automatic differentiation instead of the analytic Jacobians).
// The true geometry is paper Table 5; the start is nominal with the fixed
// coordinates xa1, ya1, xa2, ya2 at their true values (11 free).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "calib/lm.hpp"
#include "calib/paper_values.hpp"
#include "models/samples.hpp"

int main(int argc, char** argv) {
  using namespace gpm;
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_calib_lm SAMPLES.csv REPETITIONS COST\n");
    return 2;
  }
  const Samples s = read_samples_csv(argv[1]);
  const int reps = std::max(1, std::atoi(argv[2]));
  const auto cost = calib::parse_cost(argv[3]);
  if (!cost) return 2;
  const Geometry truth = calib::table5_actual();
  calib::Problem pb;
  pb.theta_m = s.theta_m;
  pb.free = default_free_mask();
  pb.start = Geometry::gpm2002_nominal();
  for (int i = 0; i < kNumParams; ++i)
    if (!pb.free.test(static_cast<size_t>(i))) pb.start[i] = truth[i];
  calib::LmOptions opt;
  opt.cost = *cost;
  opt.compute_covariance = false;
  for (int a = 4; a < argc; ++a) {
    const std::string flag = argv[a];
    if (flag == "cov") opt.compute_covariance = true;
    else if (flag == "autodiff") opt.autodiff = true;
    else if (flag != "nocov") {
      std::fprintf(stderr, "bench_calib_lm: unknown option '%s' (valid: cov, autodiff)\n", argv[a]);
      return 2;
    }
  }
  std::vector<double> t;
  calib::Result r;
  for (int k = 0; k < reps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    r = calib::calibrate_lm(pb, opt);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  double err_mm = 0.0, err_rad = 0.0;
  for (int i = 0; i < kNumParams; ++i) {
    const double e = std::abs(r.geometry[i] - truth[i]);
    (is_offset(i) ? err_rad : err_mm) = std::max(is_offset(i) ? err_rad : err_mm, e);
  }
  std::printf("median_s %.9g min_s %.9g max_err_mm %.3g max_err_rad %.3g iterations %ld evaluations %ld converged %d\n",
              t[t.size() / 2], t.front(), err_mm, err_rad, r.iterations, r.evaluations, r.converged ? 1 : 0);
  return r.converged ? 0 : 1;
}
