#include "run/offsets_first.hpp"

#include <fmt/format.h>

#include "calib/lm.hpp"
#include "models/errors.hpp"

namespace gpm::scenario {

calib::Result offsets_from_samples(const Geometry& stated, const std::vector<sim::SampleRecord>& samples) {
  if (static_cast<int>(samples.size()) < kMinFirstPassSamples)
    throw InputError(fmt::format("{} samples kept: the encoder offsets need at least {}", samples.size(),
                                 kMinFirstPassSamples));
  calib::Problem problem;
  problem.start = stated;
  for (int i = 0; i < 3; ++i) problem.free.set(static_cast<std::size_t>(dth(i)));
  for (const sim::SampleRecord& r : samples) problem.theta_m.push_back(r.theta_m);
  calib::LmOptions options;
  options.cost = calib::Cost::kML;
  return calib::calibrate_lm(problem, options);
}

}  // namespace gpm::scenario
