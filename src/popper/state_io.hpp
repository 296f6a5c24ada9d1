// Binary fields of a popper's checkpoint (same build, same machine).
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <vector>

namespace snapjump::popper {

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
}

}  // namespace snapjump::popper
