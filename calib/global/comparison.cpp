#include "calib/global/comparison.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "calib/global/synthetic.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/yaml_util.hpp"

namespace gpm::calib::global {

namespace {

double kmrmse(const Samples& s, const Geometry& g) {
  double sum = 0;
  for (size_t j = 0; j < s.size(); ++j) {
    const auto fk = forward_kinematics(g, active_from_readings(g, s.theta_m[j]));
    if (!fk) return std::numeric_limits<double>::infinity();
    sum += (fk->p - s.xy[j]).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(s.size()));
}

}  // namespace

double paper_table6(Method m, Cost c) {
  static const double v[3][3] = {{1.3447e3, 2.6869e2, 2.5351e-3},
                                 {8.9451e2, 1.0079e2, 5.5626e-14},
                                 {1.0344e2, 8.9561e0, 3.5946e-20}};
  const int ci = c == Cost::kJ1 ? 0 : c == Cost::kJ2 ? 1 : c == Cost::kJ3 ? 2 : -1;
  const int mi = m == Method::kGa ? 0 : m == Method::kPso ? 1 : 2;
  return ci < 0 ? NAN : v[ci][mi];
}

Comparison run_comparison(const ComparisonSettings& st, const ComparisonProgress& progress) {
  if (st.seeds.empty() || st.methods.empty() || st.costs.empty())
    throw InputError("compare: need at least one seed, method and cost");
  if (st.budget < 1) throw InputError("compare: the budget must be at least 1 evaluation");
  const auto t0 = std::chrono::steady_clock::now();
  Comparison c;
  c.settings = st;
  c.actual = table5_actual();
  Robot robot;
  robot.geometry = c.actual;
  c.samples = workspace_samples(robot, st.samples, st.data_seed);
  c.at_actual = closure_identifiability(c.samples.theta_m, c.actual, st.free);
  const Problem problem = table5_problem(c.samples, st.free);
  const Box box = default_box(Geometry::gpm2002_nominal(), st.free);

  for (Method m : st.methods)
    for (Cost cost : st.costs)
      for (uint64_t seed : st.seeds) c.runs.push_back({m, cost, seed, {}, 0, 0, 0});

  const int n = static_cast<int>(c.runs.size());
  std::vector<std::atomic<long>> done(static_cast<size_t>(n));
  std::atomic<int> next{0}, finished{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    for (int i; (i = next++) < n;) {
      ComparisonRun& r = c.runs[static_cast<size_t>(i)];
      try {
        GlobalOptions opt;
        opt.budget = st.budget;
        opt.seed = r.seed;
        opt.threads = 1;
        r.result = solve_global(problem, r.cost, r.method, box, opt,
                                [&done, i](long e, long, double) { done[static_cast<size_t>(i)] = e; });
        done[static_cast<size_t>(i)] = r.result.evaluations;
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
      ++finished;
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const int workers = std::clamp(st.parallel_runs > 0 ? st.parallel_runs : static_cast<int>(hw), 1, n);
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(worker);
  if (progress) {
    // The calling thread reports; the workers compute.
    pool.emplace_back(worker);
    const long total = st.budget * n;
    while (finished < n) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      long sum = 0;
      for (auto& d : done) sum += d;
      progress(sum, total, finished.load(), n);
    }
  } else {
    worker();
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);

  for (auto& r : c.runs) {
    r.kmrmse_mm = kmrmse(c.samples, r.result.geometry);
    for (int p = 0; p < kNumParams; ++p) {
      if (!st.free[static_cast<size_t>(p)]) continue;
      const double e = std::abs(r.result.geometry[p] - c.actual[p]);
      if (is_offset(p)) r.max_error_rad = std::max(r.max_error_rad, e);
      else r.max_error_mm = std::max(r.max_error_mm, e);
    }
  }
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

std::string comparison_runs_csv(const Comparison& c) {
  std::string s = "method,cost,seed,J,evaluations,seconds,rank,max_error_mm,max_error_rad,kmrmse_mm";
  for (int p = 0; p < kNumParams; ++p) s += fmt::format(",{}", param_name(p));
  s += "\n";
  for (const auto& r : c.runs) {
    s += fmt::format("{},{},{},{},{},{:.4f},{},{},{},{}", method_name(r.method), cost_name(r.cost),
                     r.seed, format_exact(r.result.final_cost), r.result.evaluations,
                     r.result.seconds, r.result.rank, format_exact(r.max_error_mm),
                     format_exact(r.max_error_rad), format_exact(r.kmrmse_mm));
    for (int p = 0; p < kNumParams; ++p) {
      s += ',';
      s += format_exact(r.result.geometry[p]);
    }
    s += "\n";
  }
  return s;
}

std::string comparison_history_csv(const Comparison& c) {
  std::string s = "method,cost,seed,evaluations,best_J\n";
  for (const auto& r : c.runs)
    for (const auto& [e, j] : r.result.history)
      s += fmt::format("{},{},{},{},{}\n", method_name(r.method), cost_name(r.cost), r.seed, e,
                       format_exact(j));
  return s;
}

}  // namespace gpm::calib::global
