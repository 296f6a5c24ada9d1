// Binary fields of a popper's checkpoint (same build, same machine).
#pragma once

#include <cmath>
#include <cstdint>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace snapjump::popper {

// 64-bit FNV-1a of the bytes.
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = 14695981039346656037ULL) {
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

template <typename T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
void get(std::istream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof v);
}
inline void put_vector(std::ostream& out, const std::vector<double>& v) {
  const std::uint64_t n = v.size();
  put(out, n);
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(n * sizeof(double)));
}
// Reads a vector that must have `expected` entries (the model's own size).
inline void get_vector(std::istream& in, std::vector<double>& v, std::size_t expected) {
  std::uint64_t n = 0;
  get(in, n);
  if (!in || n != expected)
    throw std::runtime_error("checkpoint does not match this popper's mesh");
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
  if (!in) throw std::runtime_error("the checkpoint is truncated");
  for (double x : v) {
    if (!std::isfinite(x)) throw std::runtime_error("the checkpoint holds a non-finite value");
  }
}
// Reads a value that must be finite; `what` names it in the message.
inline double get_finite(std::istream& in, const char* what) {
  double v = 0.0;
  in.read(reinterpret_cast<char*>(&v), sizeof v);
  if (!in) throw std::runtime_error("the checkpoint is truncated");
  if (!std::isfinite(v))
    throw std::runtime_error(std::string("the checkpoint's ") + what + " is not finite");
  return v;
}
// The clock of a model's state: a time >= 0 and a step count >= 0.
inline void get_clock(std::istream& in, double& time, long& steps) {
  time = get_finite(in, "time");
  in.read(reinterpret_cast<char*>(&steps), sizeof steps);
  if (!in) throw std::runtime_error("the checkpoint is truncated");
  if (time < 0.0 || steps < 0) throw std::runtime_error("the checkpoint's clock is negative");
}

}  // namespace snapjump::popper
