#include "run/offsets_first.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "calib/geometry_filter.hpp"
#include "models/errors.hpp"

namespace gpm::scenario {

OffsetsEstimate offsets_learnt(const Geometry& stated, const std::vector<sim::SampleRecord>& samples,
                               const ModelTolerance& prior) {
  constexpr double kUpdateEvery_s = 0.01;  // GeometryFilterSettings::misfit_sigma_rad's window
  if (static_cast<int>(samples.size()) < kMinFirstPassSamples)
    throw InputError(fmt::format("{} samples kept: the encoder offsets need at least {}", samples.size(),
                                 kMinFirstPassSamples));
  calib::GeometryFilterSettings settings;
  settings.prior = prior;
  calib::GeometryFilter filter(stated, settings);
  double next_s = samples.front().t_s;
  for (const sim::SampleRecord& r : samples) {
    if (r.t_s < next_s) continue;
    filter.update(r.theta_m);
    next_s = r.t_s + kUpdateEvery_s;
  }
  OffsetsEstimate out;
  out.geometry = stated;
  const std::vector<int>& free = filter.free_index();
  for (int i = 0; i < 3; ++i) {
    out.geometry[dth(i)] = filter.geometry()[dth(i)];
    const auto k = std::find(free.begin(), free.end(), dth(i)) - free.begin();
    out.sigma_rad[static_cast<std::size_t>(i)] = std::sqrt(filter.covariance()(k, k));
  }
  return out;
}

}  // namespace gpm::scenario
