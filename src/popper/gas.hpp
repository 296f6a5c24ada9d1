// The air inside the popper, isothermal:
//   delta_p = p0 (1 - J_n / J_V)   (paper, Eq. S12; outside minus inside: positive while the
//                                    inside is below atmosphere, which pushes the shell into the
//                                    container)
//   J_V = V_in / V^0,  J_n = n_in / n^0   (paper, Eq. S13),
//   V_in = container volume + cavity under the shell.
// The reference state (V^0, n^0) is the paper's: the undeformed popper at atmospheric pressure,
// i.e. V^0 = container volume + cavity of the undeformed shell, n^0 the air filling it at p0.
// At the release J_V and J_n are therefore not 1: J_n = J_V (1 - delta_p_j / p0).
// With the valve closed J_n is constant. From the release (t = 0) on, the valve law
//   d2J_n/dt2 = alpha_n delta_p,  dJ_n/dt(0) = beta_n delta_p(0)
// (the paper's empirical law, stated in the text after its Eq. S13, unnumbered) lets air in while
// the inside is below atmosphere. Since J_n counts moles in units of n^0, the reference sets the
// pace: the pressure responds to the inflow as V^0 / V_in. (The paper writes delta_p with the
// opposite sign, inside minus outside, and so has minus signs in both laws; the physics is the
// same.)
#pragma once

#include <stdexcept>

namespace snapjump::popper {

class Gas {
 public:
  // V_ref: the reference volume V^0 [m^3].
  Gas(double p0, double alpha_n, double beta_n, double V_ref)
      : p0_(p0), alpha_n_(alpha_n), beta_n_(beta_n), V_ref_(V_ref) {
    if (!(V_ref > 0.0)) throw std::invalid_argument("the reference gas volume must be positive");
  }

  // Valve closed, pressure difference held at dp (by the syringe).
  void hold(double dp) {
    open_ = false;
    delta_p_ = dp;
  }
  // t = 0: the valve opens with the gas volume V_in; the air inside is what the held pressure
  // difference leaves in that volume.
  void open_valve(double V_in) {
    if (!(V_in > 0.0)) throw std::invalid_argument("gas volume must be positive");
    J_n_ = V_in / V_ref_ * (1.0 - delta_p_ / p0_);
    J_n_rate_ = beta_n_ * delta_p_;  // dJ_n/dt(0) = beta_n delta_p(0)
    open_ = true;
  }
  // One step of the valve law (semi-implicit Euler), then the pressure at the new volume.
  void advance(double dt, double V_in) {
    if (!open_) return;
    J_n_rate_ += dt * alpha_n_ * delta_p_;  // d2J_n/dt2 = alpha_n delta_p
    J_n_ += dt * J_n_rate_;
    delta_p_ = p0_ * (1.0 - J_n_ * V_ref_ / V_in);  // (paper, Eqs. S12 and S13)
  }

  [[nodiscard]] double delta_p() const { return delta_p_; }
  [[nodiscard]] bool valve_open() const { return open_; }
  [[nodiscard]] double J_n() const { return J_n_; }
  [[nodiscard]] double J_n_rate() const { return J_n_rate_; }
  [[nodiscard]] double V_ref() const { return V_ref_; }
  // Restores a saved state (checkpoints); the reference volume is the popper's own.
  void restore(double delta_p, bool open, double J_n, double J_n_rate) {
    delta_p_ = delta_p;
    open_ = open;
    J_n_ = J_n;
    J_n_rate_ = J_n_rate;
  }

 private:
  double p0_, alpha_n_, beta_n_, V_ref_;
  double delta_p_ = 0.0;
  bool open_ = false;
  double J_n_ = 1.0, J_n_rate_ = 0.0;
};

}  // namespace snapjump::popper
