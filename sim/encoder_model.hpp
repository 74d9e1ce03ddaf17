// Absolute encoder of one active joint, as a drive reports it:
//   reading = wrap_[0, 2 pi)( quantise( theta_a - dth + noise ) )
// with dth the actual zero offset (paper eq. 35: theta_a = theta_m + dth),
// quantisation to 2^bits x N counts per joint revolution (the encoder sits on
// the motor, N = gear ratio, motor revolutions per joint revolution; N = 1
// unless given; bits = 0: ideal, no quantisation) and optional Gaussian noise
// (gpm::Rng, explicit seed, so runs are bit-reproducible).
#pragma once

#include "models/rng.hpp"

namespace gpm::sim {

// Constant settings of the encoders (shared by the three joints).
struct EncoderModel {
  int bits = 17;           // counts per revolution = 2^bits; 0 = ideal
  double noise_rad = 0.0;  // standard deviation of additive Gaussian noise

  // One count in radians (0 for an ideal encoder).
  double count_rad() const;
};

// Mutable noise source of the encoders.
struct EncoderNoise {
  explicit EncoderNoise(unsigned long long seed) : rng(seed) {}
  Rng rng;
};

// Wraps and quantises an angle to the nearest count in [0, 2 pi) (one count per motor count, N = 1).
double quantise_reading(const EncoderModel& model, double angle);

// Wraps and quantises a joint angle to the nearest of the 2^bits x gear_ratio counts of a joint revolution.
double quantise_reading(const EncoderModel& model, double angle, double gear_ratio);

// One reading of a joint at true angle theta_a whose encoder zero is offset by
// dth, behind gear_ratio motor revolutions per joint revolution. Draws from
// noise only when noise_rad > 0.
double encoder_reading(const EncoderModel& model, EncoderNoise& noise, double theta_a, double dth,
                       double gear_ratio = 1.0);

}  // namespace gpm::sim
