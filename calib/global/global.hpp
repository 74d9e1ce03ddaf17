// Global calibration (paper section 4): GA, PSO or DE on J1, J2 or J3 within a
// search box and a budget of error-function evaluations.
//
//   Problem p{readings, start, free};            // start: fixed values known
//   Box box = default_box(Geometry::gpm2002_nominal(), p.free);   // Table 5
//   Result r = solve_global(p, Cost::kJ3, Method::kDe, box, {.budget = 1'500'000, .seed = 7});
//
// r.geometry holds all 15 parameters, r.history (evaluations, best J), and
// r.rank / r.notes the identifiability diagnosis at the found point.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "calib/global/de.hpp"
#include "calib/global/ga.hpp"
#include "calib/global/objective.hpp"
#include "calib/global/pso.hpp"
#include "calib/problem.hpp"

namespace gpm::calib::global {

enum class Method { kGa, kPso, kDe };

// "ga", "pso", "de" -> Method; nullopt for anything else.
std::optional<Method> parse_method(std::string_view name);
std::string_view method_name(Method m);

struct GlobalOptions {
  long budget = 1'500'000;  // error-function evaluations, never exceeded
  uint64_t seed = 1;
  int threads = 0;          // 0 = all cores; results do not depend on it
  double target = -std::numeric_limits<double>::infinity();  // stop once best J <= target
  GaSettings ga;            // paper section 4.4 defaults
  PsoSettings pso;
  DeSettings de;
};

// Minimises J (cost: kJ1, kJ2 or kJ3) over the free parameters of problem
// within box with the given method; fixed parameters keep problem.start.
// Throws InputError for an unsupported cost, an empty box or a budget < 1.
Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box,
                    const GlobalOptions& options, const ProgressFn& progress = {});

// The same with default settings, budget and seed.
Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box, long budget,
                    uint64_t seed, const ProgressFn& progress = {});

}  // namespace gpm::calib::global
