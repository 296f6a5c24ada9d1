// Cases the tests share.
#pragma once

#include "config/case.hpp"

namespace snapjump::test_support {

// The default popper on the cheap axisymmetric coarse preset.
inline config::Case coarse_axisymmetric_default() {
  auto c = config::default_case();
  c.numerics.model = config::Model::Axisymmetric;
  c.numerics.resolution = config::Resolution::Coarse;
  return c;
}

}  // namespace snapjump::test_support
