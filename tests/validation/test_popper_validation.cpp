// The popper's preparation against what the protocol must achieve: the shell inverts, holds at
// delta_p_j, and once grounded the plate carries the net weight (a force balance nobody here
// wrote). About a minute on two cores.
#include <gtest/gtest.h>

#include <cmath>

#include "popper/popper.hpp"
#include "theory/scaling.hpp"

namespace snapjump::popper {
namespace {

TEST(PopperValidation, DefaultPopperPreparesAndCarriesItsWeight) {
  auto c = config::default_case();
  c.numerics.resolution = config::Resolution::Coarse;
  Popper pop(c, resolve_numerics(c));
  const auto prep = pop.prepare();
  ASSERT_TRUE(prep.inverted) << prep.message;
  ASSERT_TRUE(prep.held) << prep.message;
  EXPECT_NEAR(prep.plate_force / c.popper.net_weight, 1.0, 0.02) << prep.message;
  pop.release();
  const auto s = pop.sample();
  EXPECT_DOUBLE_EQ(s.t, 0.0);
  EXPECT_DOUBLE_EQ(s.z, 0.0);
  EXPECT_NEAR(s.delta_p, theory::jump_pressure(c), 1e-9);
  EXPECT_EQ(s.contact, measure::ContactState::Ring);  // an inverted shell stands on its rim fold
  // The apex of the inverted shell is far above the plate, about the cap's depth.
  EXPECT_GT(s.w, 0.5 * theory::cap_depth(c.shell.R, c.shell.phi));
}

}  // namespace
}  // namespace snapjump::popper
