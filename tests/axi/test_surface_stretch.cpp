// The inner surface's stretches against homogeneous deformations, whose gradient is known.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "axi/surface_stretch.hpp"

namespace snapjump::axi {
namespace {

Body cap() {
  return Body(
      {.R = 0.030, .h = 0.002, .phi = 80.0 * std::numbers::pi / 180.0, .through = 2, .along = 21},
      fem::Material::from_young(1.2e6, 0.45, 1160.0));
}

TEST(SurfaceStretch, AStretchOfTheMeridianPlaneIsReadAtEveryPoint) {
  // r = a R, z = b Z: F = diag(a, b) everywhere, so the principal stretches are a and b, and the
  // stretch along the surface with unit tangent T is sqrt(a^2 T_r^2 + b^2 T_z^2).
  const auto body = cap();
  const double a = 0.7, b = 1.3;
  Points x = body.nodes();
  for (std::size_t i = 0; i < x.size(); ++i) {
    x.r[i] *= a;
    x.z[i] *= b;
  }
  const auto st = inner_surface_stretches(body, x, 3);
  ASSERT_EQ(st.size(), 63u);
  const double radius = 0.029, phi = 80.0 * std::numbers::pi / 180.0;
  for (const auto& s : st) {
    EXPECT_NEAR(s.ratio, b / a, 1e-12);
    const double theta = phi - s.from_rim / radius;  // the surface's polar angle
    // The tangent of the circle (R, Z) = radius (sin theta, -cos theta).
    const double expected = std::hypot(a * std::cos(theta), b * std::sin(theta));
    EXPECT_NEAR(s.tangential, expected, 1e-3);  // the quadratic segment's tangent, not the arc's
    EXPECT_EQ(s.compressed, expected - a < b - expected);
  }
  EXPECT_NEAR(st.front().from_rim, radius * phi, 1e-12);
  EXPECT_NEAR(st.back().from_rim, 0.0, 1e-12);
  // Compressed along the surface near the apex (T along r) and not near the rim (T mostly along z).
  EXPECT_TRUE(st.front().compressed);
  EXPECT_FALSE(st.back().compressed);
  const auto worst = largest_compressed_ratio(st);
  EXPECT_NEAR(worst.ratio, b / a, 1e-12);
  EXPECT_TRUE(worst.compressed);
}

TEST(SurfaceStretch, ARotationStretchesNothing) {
  // A rigid rotation of the meridian plane (not an axisymmetric motion, but a map all the same):
  // every stretch is 1 and no point counts as compressed.
  const auto body = cap();
  const double c = std::cos(0.4), s = std::sin(0.4);
  Points x = body.nodes();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = x.r[i], z = x.z[i];
    x.r[i] = c * r - s * z;
    x.z[i] = s * r + c * z;
  }
  for (const auto& p : inner_surface_stretches(body, x)) {
    EXPECT_NEAR(p.ratio, 1.0, 1e-9);
    EXPECT_NEAR(p.tangential, 1.0, 1e-9);
  }
  EXPECT_TRUE(std::isnan(largest_compressed_ratio(inner_surface_stretches(body, x)).from_rim));
}

TEST(SurfaceStretch, FewerThanTwoPointsAreRefused) {
  const auto body = cap();
  EXPECT_THROW(static_cast<void>(inner_surface_stretches(body, body.nodes(), 1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace snapjump::axi
