// The shell body's material from a case: its small-strain moduli and its law.
#pragma once

#include "config/case.hpp"
#include "fem/body.hpp"

namespace snapjump::popper {

inline fem::Material body_material(const config::Material& m) {
  const auto body = fem::Material::from_young(m.E, m.nu, m.rho);
  return m.law == config::Law::Gent ? body.with_gent(m.gent_jm.value()) : body;
}

}  // namespace snapjump::popper
