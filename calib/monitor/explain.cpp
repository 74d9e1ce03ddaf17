#include "calib/monitor/explain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gpm::calib::monitor {

void explain_window(const MonitorModel& model, const MonitorData& data, Alarm& alarm) {
  std::array<double, kNumParams> s_zh{}, s_hh{}, inv_d0_sq{};
  for (int k = 0; k < model.n_free; ++k) {
    const int i = model.free_index[static_cast<size_t>(k)];
    const double d0 = is_offset(i) ? model.settings.jump_offset_rad : model.settings.jump_length_mm;
    inv_d0_sq[static_cast<size_t>(k)] = 1.0 / (d0 * d0);
  }
  double s_zz = 0.0;
  alarm.score = -std::numeric_limits<double>::infinity();
  for (int j = data.count - 1; j >= 0; --j) {  // onset at window sample j: samples j..end
    const int slot = (data.head - data.count + j + 2 * kMaxWindow) % kMaxWindow;
    const double z = data.z[static_cast<size_t>(slot)];
    const ParamRow& dz = data.dz[static_cast<size_t>(slot)];
    s_zz += z * z;
    for (int k = 0; k < model.n_free; ++k) {
      const auto ks = static_cast<size_t>(k);
      const int i = model.free_index[ks];
      s_zh[ks] += dz[i] * z;
      s_hh[ks] += dz[i] * dz[i];
      // The change that raised the alarm began at or before it: later onsets
      // only add their samples to the sums.
      if (data.t[static_cast<size_t>(slot)] > alarm.t_s) continue;
      const double denom = s_hh[ks] + inv_d0_sq[ks];
      const double fit = s_zh[ks] * s_zh[ks] / denom;
      if (fit <= alarm.score) continue;  // the log term is >= 0: cannot win
      const double score = fit - std::log(denom / inv_d0_sq[ks]);
      if (score > alarm.score) {
        alarm.score = score;
        alarm.param = i;
        alarm.delta = -s_zh[ks] / denom;
        alarm.onset_s = data.t[static_cast<size_t>(slot)];
        alarm.explained = s_zz > 0.0 ? fit / s_zz : 0.0;
      }
    }
  }
}

double step_statistic(const MonitorModel& model, const FilterWindow& data, ParamRow* per_param_max) {
  std::array<double, kNumParams> s_zh{}, s_hh{}, s_hf{}, var{};
  for (int k = 0; k < model.n_free; ++k) {
    const double sd = 1.0 / model.scale[static_cast<size_t>(k)];
    var[static_cast<size_t>(k)] = data.P(k, k) * sd * sd;
  }
  double best = 0.0;
  const bool bound = model.settings.step_shared_bound;
  const int last_onset = data.count - model.settings.step_min_samples;  // onsets with enough samples after them
  const double clip = model.settings.step_clip > 0.0 ? model.settings.step_clip : std::numeric_limits<double>::infinity();
  for (int j = data.count - 1; j >= 0; --j) {
    const int slot = (data.head - data.count + j + 2 * kMaxWindow) % kMaxWindow;
    const double z = std::clamp(data.z[static_cast<size_t>(slot)], -clip, clip);
    const ParamRow& dz = data.dz[static_cast<size_t>(slot)];
    const double f = data.z_filter[static_cast<size_t>(slot)];
    for (int k = 0; k < model.n_free; ++k) {
      const auto ks = static_cast<size_t>(k);
      const int i = model.free_index[ks];
      s_zh[ks] += dz[i] * z;
      s_hh[ks] += dz[i] * dz[i];
      s_hf[ks] += std::abs(dz[i]) * f;
      if (j <= last_onset && s_hh[ks] > 0.0) {
        // Var(S_zh): S_hh (each sample's own noise) plus that of the filter's
        // error all samples share: S_hh^2 P_ii if it lay along i alone, at
        // most (sum |dz_i| z_filter)^2 whatever it is (Cauchy-Schwarz).
        const double variance =
            bound ? s_hh[ks] + std::min(s_hh[ks] * s_hh[ks] * var[ks], s_hf[ks] * s_hf[ks])
                  : s_hh[ks] * (1.0 + s_hh[ks] * var[ks]);
        const double term = s_zh[ks] * s_zh[ks] / (variance * data.step_factor[i]);
        best = std::max(best, term);
        if (per_param_max) (*per_param_max)[i] = std::max((*per_param_max)[i], term);
      }
    }
  }
  return best;
}

}  // namespace gpm::calib::monitor
