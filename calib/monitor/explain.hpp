// Explanation of a change-test alarm: which single parameter, changed by how
// much from which sample on, best explains the innovations in the window.
#pragma once

#include "calib/monitor/monitor.hpp"

namespace gpm::calib::monitor {

// Bayesian comparison over (parameter i, onset k): a change delta of
// parameter i from window sample k on shifts the innovations by
// -dz_j[i] delta (j >= k; to first order r(x + delta e_i) = r(x) + dr/dx_i
// delta = 0 for readings of the changed robot). With the prior delta ~
// N(0, d0^2) (d0 = jump_offset_rad or jump_length_mm), the log evidence
// against "no change" is
//   score = S_zh^2 / (S_hh + d0^-2) - log(1 + d0^2 S_hh),
//   S_zh = sum_{j>=k} dz_j[i] z_j,  S_hh = sum_{j>=k} dz_j[i]^2,
// and the posterior mean delta = -S_zh / (S_hh + d0^-2). Over a short window
// the sensitivity columns are nearly collinear; the prior keeps a column
// that needs an implausibly large change (a base joint moved by millimetres)
// from winning over one that fits with a plausible one. Fills param, delta,
// onset_s (never after alarm.t_s), explained and score of `alarm`. Allocation-free.
void explain_window(const MonitorModel& model, const MonitorData& data, Alarm& alarm);

// The step test's statistic: the generalised likelihood ratio of a step in
// one estimated parameter from some onset in the window against no change,
//   max over (i, k) of S_zh^2 / (S_hh (1 + S_hh P_ii))   (sums as above, no prior;
//   onsets k with at least settings.step_min_samples samples from k on: a
//   step persists, a point of the job where the reading model fails does not),
// with P_ii the filter's variance of parameter i: the window's innovations
// share the filter's error, which adds S_hh^2 P_ii to the variance of S_zh
// if it lies along parameter i alone. With settings.step_shared_bound the
// denominator is S_hh + min(S_hh^2 P_ii, S_hf^2), S_hf = sum |dz_i| z_filter:
// S_hf^2 bounds that variance whatever the error (Cauchy-Schwarz, z_filter
// each sample's share of its spread). Each term is taken as chi-square with 1
// degree of freedom. After the learning phase each parameter's term is
// divided by data.step_factor[i], the variance factor of such sums learnt
// from the robot (learning.hpp). Allocation-free, O(window * n_free).
// per_param_max (optional): each parameter's largest term is raised to at
// least its value (the learning phase keeps them).
double step_statistic(const MonitorModel& model, const FilterWindow& data, ParamRow* per_param_max = nullptr);

}  // namespace gpm::calib::monitor
