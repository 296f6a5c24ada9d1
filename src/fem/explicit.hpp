// A plain explicit driver for the body alone: m a = f_ext + f_int (paper, Eq. S8) by central
// differences (leapfrog), with optional
// mass-proportional damping, the rim clamped to a frame that may move along z. Used by the
// tests and by quasi-static preparation phases.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <unordered_map>

#include "core/container_face.hpp"
#include "fem/body.hpp"
#include "parallel/threads.hpp"

namespace snapjump::fem {

struct ExplicitOptions {
  double dt = 0.0;                // time step [s]; 0: stable_time_step(time_step_factor)
  double time_step_factor = 0.3;  // used when dt = 0
  double damping = 0.0;           // mass-proportional damping coefficient c [1/s]: m a = f - c m v
  double gravity = 0.0;           // [m/s^2], acting along -z
  // Pressure difference (outside minus inside) on the inner faces as a function of time [Pa].
  std::function<double(double)> pressure;
  // Displacement of the clamp frame along z as a function of time, and its velocity [m, m/s].
  std::function<double(double)> clamp_z;
  std::function<double(double)> clamp_vz;
  // Instead of the rigid z motion: a fixed displacement of each clamped node (node index ->
  // displacement), e.g. an exact solution imposed on the rim for a validation.
  std::function<std::array<double, 3>(int)> clamp_displacement;
  // The container's bottom face, moving with the clamp frame: a node whose step would end across
  // it ends on it, its normal speed taken out (frictionless). Absent: nothing stops the shell
  // there.
  std::optional<core::ContainerFace> container_face;
  // Choose between one thread and the most allowed by timing both (parallel::ThreadTuner);
  // the results are the same either way.
  bool tune_threads = true;
};

class ExplicitDriver {
 public:
  ExplicitDriver(const Body& body, ExplicitOptions options);

  // Advances one step. Throws InvertedElement; positions and velocities stay as before the step.
  void step();
  // Steps until time >= t_end; calls observe(*this) every `every` steps if given.
  void run_until(double t_end, const std::function<void(const ExplicitDriver&)>& observe = {},
                 int every = 1);

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] double dt() const { return dt_; }
  [[nodiscard]] long steps() const { return steps_; }
  [[nodiscard]] const mesh::Points& positions() const { return x_; }
  [[nodiscard]] const mesh::Points& velocities() const { return v_; }
  [[nodiscard]] double kinetic_energy() const;
  [[nodiscard]] const Body& body() const { return body_; }
  [[nodiscard]] const parallel::ThreadTuner& thread_tuner() const { return tuner_; }
  // How many nodes the container's face stopped in the last step, and how far the deepest of them
  // would have crossed it [m] (0 when none).
  [[nodiscard]] int face_contacts() const { return face_contacts_; }
  [[nodiscard]] double face_depth() const { return face_depth_; }

 private:
  void advance();  // one step at the current thread count
  // Takes out the normal speed of node a (at the step's start, moving at its new velocity) that
  // would carry it across the face of a container at dz; returns the depth it would have
  // crossed by [m], 0 when none.
  double stop_at_face(const core::ContainerFace& face, std::size_t a, double dz);
  const Body& body_;
  ExplicitOptions options_;
  double dt_ = 0.0;
  double time_ = 0.0;
  long steps_ = 0;
  mesh::Points x_, v_, f_;
  std::vector<char> clamped_;
  std::unordered_map<int, std::array<double, 3>> clamp_offset_;  // from clamp_displacement
  parallel::ThreadTuner tuner_;
  Body::ForceScratch scratch_;
  int face_contacts_ = 0;
  double face_depth_ = 0.0;
};

}  // namespace snapjump::fem
