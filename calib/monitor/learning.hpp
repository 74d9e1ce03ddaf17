// The monitor's learning phase (issue 31): what the monitor learns from the
// robot itself, during the first seconds of normal operation, about how far
// its readings depart from the reading model it was given (the data sheet
// or the calibration's estimates).
//
// The monitor has one channel: the normalised ML innovation z of the
// closure of the three readings (monitor.hpp; three encoders, one
// redundancy). Under the stated model z ~ N(0, 1), independent from sample to
// sample. A real robot of the class departs from it in three ways, each
// learnt here from the innovations of the learning phase:
//   - scale: z has a larger spread (backlash, transmission error, encoder
//     harmonics the model leaves out). Learnt robustly as 1.4826 x the median
//     absolute deviation about the median (a slip or an outlier in the
//     learning phase moves it little), bounded below by 1: the stated model
//     (quantisation and what the data sheet or the calibration stated) is a
//     floor, never narrowed. The monitor does not know the scale exactly:
//     its upper confidence bound (MAD's relative standard error 1.1 /
//     sqrt(n_eff), two of them) is what the tests use;
//   - bias: z has a non-zero level (a reading error of one sign along the
//     job). Learnt as the median, then followed slowly (monitor.hpp);
//   - correlation: the reading errors of neighbouring samples are alike (a
//     drive train's error follows the motion), so a sum over a window
//     varies more than independent samples would. Learnt by batch means:
//     for the step test along each parameter, the mean over batches of the
//     squared matched sum (sum h z')^2 / sum h^2 (matched_sum_factor; 1 for
//     independent samples), B var(batch mean of z') as the correlation
//     factor of the scale's uncertainty, and the mean and variance of batch sums of z'^2 for the
//     chi-square (its Satterthwaite factor), z' = (z - median) / scale,
//     batches of B samples; each at least 1 and widened by its own
//     uncertainty (a chi-square bound over the number of batches).
// Pure arithmetic on a buffer; allocation-free (the caller gives scratch).
#pragma once

#include <cmath>

namespace gpm::calib::monitor {

struct LearnedScale {
  int samples = 0;            // innovations learnt from
  double median = 0.0;        // their median (z units): the learnt bias
  double mad_scale = 1.0;     // 1.4826 x median absolute deviation about the median (z units)
  double scale = 1.0;         // what the tests use: max(floor, upper bound of mad_scale)
  // Variance factor of batch means of z' (>= 1, widened by its uncertainty);
  // after monitor.cpp's learning phase, the largest of the step test's
  // per-parameter factors (matched_sum_factor) instead.
  double step_factor = 1.0;
  // The chi-square statistic sum z''^2 over W samples, z'' = (z - median) /
  // scale, is taken as chi_factor x chi2 with W chi_mean / chi_factor
  // degrees of freedom (Satterthwaite: mean W chi_mean, variance as the
  // batch sums say), each widened by its uncertainty.
  double chi_mean = 1.0;
  double chi_factor = 1.0;
  double effective_samples = 0.0;  // samples / step_factor (before widening)
  // The configuration map (config_map.hpp, monitor.cpp): whether the monitor
  // tests on the residual less the map, and how many learnt samples of the
  // last three quarters another pass matched.
  bool map = false;
  int map_matched = 0;
};

// Learns from z[0..n) (n >= 2; z is not modified) with batches of `batch`
// samples; scale_floor (>= 1) is the least scale allowed. scratch must hold
// n doubles. Allocation-free, O(n) (two nth_element).
LearnedScale learn_innovation_scale(const double* z, int n, int batch, double scale_floor, double* scratch);

// Sums of one batch of learnt samples along one parameter's signature h
// (the step test's building blocks): sum h, sum h z, sum h^2.
struct MatchedBatch {
  double h = 0.0, hz = 0.0, hh = 0.0;
};

// The batch terms behind a step factor: their sum and how many there are.
struct MatchedTerms {
  double sum = 0.0;
  int count = 0;
};

// The terms (sum h (z - median))^2 / (scale^2 sum h^2) of `batches` batches
// (those with sum h^2 > 0). batch(b) returns the MatchedBatch of batch b.
template <class BatchOf>
MatchedTerms matched_terms(int batches, double median, double scale, const BatchOf& batch) {
  MatchedTerms t;
  for (int b = 0; b < batches; ++b) {
    const MatchedBatch m = batch(b);
    if (!(m.hh > 0.0)) continue;
    const double s = m.hz - median * m.h;
    t.sum += s * s / (scale * scale * m.hh);
    ++t.count;
  }
  return t;
}

// The factor of terms: their mean widened by one standard error
// sqrt(2 / (count - 1)), never below 1 (1 with fewer than 2 terms).
inline double matched_factor(const MatchedTerms& t) {
  if (t.count < 2) return 1.0;
  const double f = t.sum / t.count * (1.0 + std::sqrt(2.0 / (t.count - 1)));
  return f > 1.0 ? f : 1.0;
}

// The step test's variance factor along one parameter: the mean over
// `batches` batches of (sum h (z - median))^2 / (scale^2 sum h^2), which is 1
// for independent innovations of that scale (whatever h) and the
// batch-means variance factor for correlated ones with a constant h; widened
// by one standard error sqrt(2 / (batches - 1)), never below 1 (1 with fewer
// than 2 batches). batch(b) returns the MatchedBatch of batch b.
template <class BatchOf>
double matched_sum_factor(int batches, double median, double scale, const BatchOf& batch) {
  return matched_factor(matched_terms(batches, median, scale, batch));
}

// Upper quantile of a chi-square with dof degrees of freedom (any dof > 0) at
// the tail probability whose standard normal upper quantile is z_p, by the
// Wilson-Hilferty cube-root approximation (relative error below 1e-3 for
// dof >= 50 at the monitor's tail probabilities). Allocation-free.
double chi2_quantile_wilson_hilferty(double dof, double z_p);

// The standard normal quantile z_p that the Wilson-Hilferty formula maps to
// threshold at dof (its inverse).
double wilson_hilferty_normal_quantile(double dof, double threshold);

}  // namespace gpm::calib::monitor
