#include <gtest/gtest.h>

#include "config/case.hpp"
#include "popper/popper.hpp"

namespace snapjump::popper {
namespace {

// Each model keeps its own integration of the bulk energy unless the case names one: the 3D
// tetrahedra the paper's full rule, the axisymmetric elements their reduced one.
TEST(Numerics, EachModelHasItsOwnBulkIntegrationUnlessTheCaseSetsOne) {
  auto c = config::default_case();
  EXPECT_FALSE(resolve_numerics(c).reduced_bulk);
  c.numerics.model = config::Model::Axisymmetric;
  EXPECT_TRUE(resolve_numerics(c).reduced_bulk);
  c.numerics.bulk_integration = config::BulkIntegration::Full;
  EXPECT_FALSE(resolve_numerics(c).reduced_bulk);
  c.numerics.model = config::Model::ThreeD;
  c.numerics.bulk_integration = config::BulkIntegration::Reduced;
  EXPECT_TRUE(resolve_numerics(c).reduced_bulk);
}

// The presets' grid and axisymmetric elements come from the one table, config::preset.
TEST(Numerics, ThePresetsSetTheGridAndTheAxisymmetricElements) {
  auto c = config::default_case();
  for (const auto r :
       {config::Resolution::Coarse, config::Resolution::Default, config::Resolution::Fine}) {
    c.numerics.resolution = r;
    const auto n = resolve_numerics(c);
    EXPECT_DOUBLE_EQ(
        n.dx, std::min(c.shell.h / config::preset(r).grid_cells_per_thickness, n.cap.element_size));
    EXPECT_EQ(n.axi_through, config::preset(r).axi_through);
    EXPECT_EQ(n.cap.layers, config::preset(r).layers);
  }
  EXPECT_EQ(config::preset(config::Resolution::Default).grid_cells_per_thickness, 4.0);
  EXPECT_EQ(config::preset(config::Resolution::Fine).layers, 2);
}

}  // namespace
}  // namespace snapjump::popper
