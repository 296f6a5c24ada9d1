// The Morton (z-order) curve: three 21-bit integer coordinates interleaved into one 63-bit key.
// Points whose keys are close lie close together; sorting by key orders them along the curve.
#pragma once

#include <cstdint>

namespace snapjump::core {

// Spreads the low 21 bits of v to every third bit (bit i to bit 3i).
constexpr std::uint64_t spread_bits_3(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// The key of the cell (x, y, z), each in [0, 2^21): x in the highest bit of each triple.
constexpr std::uint64_t morton_key(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return spread_bits_3(x) << 2 | spread_bits_3(y) << 1 | spread_bits_3(z);
}

}  // namespace snapjump::core
