// Signal helpers of the analysis (measure/analysis.hpp): interpolation, robust spreads, the walk
// along a force's rise. Internal to the measure layer; docs/analysis.md states the rules they
// implement.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace snapjump::measure::signal {

// y linearly interpolated at tq, held constant outside [t.front(), t.back()].
double interpolate(std::span<const double> t, std::span<const double> y, double tq);

// Time where the segment (i - 1, i) crosses `level`, assuming y[i - 1] and y[i] lie on either
// side.
double crossing_time(std::span<const double> t, std::span<const double> y, std::size_t i,
                     double level);

// A robust standard deviation: 1.4826 times the median absolute deviation from the median
// (equal to the standard deviation for Gaussian noise, blind to a few impact spikes).
double robust_sigma(std::vector<double> v);

// The upper of the two middle values (the middle one for an odd count); v not empty.
double upper_median(std::vector<double> v);

// The upper median of y[from, to); to > from.
double median_of(std::span<const double> y, std::size_t from, std::size_t to);

// The fewest samples a noise estimate or a median of a stretch rests on.
inline constexpr std::size_t kMinNoiseSamples = 5;

// The plate's noise wherever the popper is (resting, rocking, in flight): the robust spread of
// F's changes from sample to sample over sqrt(2). A force that varies slowly against the sampling
// changes little between samples, and impacts are few. 0 for fewer than six samples.
double sample_noise(std::span<const double> F);

// How much higher z goes after the last sample: a least-squares parabola through the last samples
// (up to 21) gives the velocity at the end and the deceleration. Infinity when z is not slowing
// down, or when the curvature is not clearly resolved (less than three standard errors, as on a
// noisy measured record).
double rise_left(std::span<const double> t, std::span<const double> z);

// The walk along a rise of F. Walking back from sample k, the extreme F met (the lowest for
// sign = +1, the highest for sign = -1) before F turns back by more than `turn`: a tenth of the
// way from that extreme to F[k] (kTurnFraction), and at least `noise_floor` (the plate's noise
// times the noise multiple, so that noise near a rounded peak, where the way is still short, does
// not end the walk).
inline constexpr double kTurnFraction = 0.1;
std::size_t extreme_behind(std::span<const double> F, std::size_t k, double sign,
                           double noise_floor);

// The start of the rise of F that ends at sample `k`: F_b is the lowest F met walking back from k
// (extreme_behind); the rise starts where F, walking back from k, first falls below
// F_b + 0.1 (F[k] - F_b): the index of that sample (k itself when F[k] is the base), the level, and
// the base's index.
struct RiseStart {
  std::size_t index;
  double level;
  std::size_t base;
};
RiseStart rise_start(std::span<const double> F, std::size_t k, double noise_floor);

// The foot's time: the interpolated crossing of the rise's level, or t[k] when F[k] is the base.
double rise_time(std::span<const double> t, std::span<const double> F, std::size_t k,
                 const RiseStart& r);

// The force peak that sample `k` lies on or after (extreme_behind with sign -1).
std::size_t peak_behind(std::span<const double> F, std::size_t k, double noise_floor);

// The longest stretch of at least min_time where F < -level. Returns (first, last) indices.
std::optional<std::pair<std::size_t, std::size_t>> negative_stretch(std::span<const double> t,
                                                                    std::span<const double> F,
                                                                    double level, double min_time);

}  // namespace snapjump::measure::signal
