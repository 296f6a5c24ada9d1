#include "measure/signal.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace snapjump::measure::signal {

double interpolate(std::span<const double> t, std::span<const double> y, double tq) {
  if (tq <= t.front()) return y.front();
  if (tq >= t.back()) return y.back();
  const auto it = std::upper_bound(t.begin(), t.end(), tq);
  const auto i = static_cast<std::size_t>(it - t.begin());  // t[i - 1] <= tq < t[i]
  const double s = (tq - t[i - 1]) / (t[i] - t[i - 1]);
  return y[i - 1] + s * (y[i] - y[i - 1]);
}

double crossing_time(std::span<const double> t, std::span<const double> y, std::size_t i,
                     double level) {
  const double dy = y[i] - y[i - 1];
  if (dy == 0.0) return t[i];
  const double s = std::clamp((level - y[i - 1]) / dy, 0.0, 1.0);
  return t[i - 1] + s * (t[i] - t[i - 1]);
}

double robust_sigma(std::vector<double> v) {
  const auto median = [](std::vector<double>& x) {
    const auto mid = x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2);
    std::nth_element(x.begin(), mid, x.end());
    double m = *mid;
    if (x.size() % 2 == 0) m = 0.5 * (m + *std::max_element(x.begin(), mid));
    return m;
  };
  const double m = median(v);
  for (auto& x : v) x = std::abs(x - m);
  return 1.4826 * median(v);
}

double upper_median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double median_of(std::span<const double> y, std::size_t from, std::size_t to) {
  return upper_median(std::vector<double>(y.begin() + static_cast<std::ptrdiff_t>(from),
                                          y.begin() + static_cast<std::ptrdiff_t>(to)));
}

double sample_noise(std::span<const double> F) {
  if (F.size() < kMinNoiseSamples + 1) return 0.0;
  std::vector<double> d(F.size() - 1);
  for (std::size_t i = 0; i + 1 < F.size(); ++i) d[i] = F[i + 1] - F[i];
  return robust_sigma(std::move(d)) / std::sqrt(2.0);
}

double rise_left(std::span<const double> t, std::span<const double> z) {
  const std::size_t n = z.size();
  const std::size_t k = std::min<std::size_t>(n, 21);
  constexpr double kUnknown = std::numeric_limits<double>::infinity();
  if (k < 5) return kUnknown;
  Eigen::MatrixXd X(k, 3);
  Eigen::VectorXd y(k);
  const double scale = t[n - 1] - t[n - k];  // tau in units of the window, for conditioning
  if (!(scale > 0.0)) return kUnknown;
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = n - k + i;
    const double tau = (t[j] - t[n - 1]) / scale;
    X(static_cast<Eigen::Index>(i), 0) = 1.0;
    X(static_cast<Eigen::Index>(i), 1) = tau;
    X(static_cast<Eigen::Index>(i), 2) = tau * tau;
    y(static_cast<Eigen::Index>(i)) = z[j];
  }
  const Eigen::Matrix3d inv = (X.transpose() * X).inverse();  // 3 x 3, tau scaled to [-1, 0]
  const Eigen::Vector3d c = inv * (X.transpose() * y);
  const double rss = (X * c - y).squaredNorm();
  const double var_c2 = rss / static_cast<double>(k - 3) * inv(2, 2);
  const double v_end = c(1) / scale;  // dz/dt at the last sample
  const double decel = -2.0 * c(2) / (scale * scale);
  if (!(decel > 0.0) || c(2) * c(2) <= 9.0 * var_c2) return kUnknown;
  return v_end > 0.0 ? v_end * v_end / (2.0 * decel) : 0.0;
}

std::size_t extreme_behind(std::span<const double> F, std::size_t k, double sign,
                           double noise_floor) {
  std::size_t best = k;
  for (std::size_t i = k; i-- > 0;) {
    const double d = sign * (F[i] - F[best]);  // < 0: further along; > 0: turning back
    if (d < 0.0) {
      best = i;
    } else if (d > std::max(kTurnFraction * sign * (F[k] - F[best]), noise_floor)) {
      break;
    }
  }
  return best;
}

RiseStart rise_start(std::span<const double> F, std::size_t k, double noise_floor) {
  const std::size_t low = extreme_behind(F, k, +1.0, noise_floor);
  const double level = F[low] + kTurnFraction * (F[k] - F[low]);
  std::size_t i = k;
  while (i > low && F[i] > level) --i;
  return {i, level, low};
}

double rise_time(std::span<const double> t, std::span<const double> F, std::size_t k,
                 const RiseStart& r) {
  return r.index < k ? crossing_time(t, F, r.index + 1, r.level) : t[k];
}

std::size_t peak_behind(std::span<const double> F, std::size_t k, double noise_floor) {
  return extreme_behind(F, k, -1.0, noise_floor);
}

std::optional<std::pair<std::size_t, std::size_t>> negative_stretch(std::span<const double> t,
                                                                    std::span<const double> F,
                                                                    double level, double min_time) {
  std::optional<std::pair<std::size_t, std::size_t>> best;
  double best_span = min_time;
  for (std::size_t i = 0; i < F.size();) {
    if (!(F[i] < -level)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < F.size() && F[j + 1] < -level) ++j;
    if (t[j] - t[i] >= best_span) {
      best = std::make_pair(i, j);
      best_span = t[j] - t[i];
    }
    i = j + 1;
  }
  return best;
}

}  // namespace snapjump::measure::signal
