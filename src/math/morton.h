// 3D Morton (Z-order) codes: neighbours along the curve are neighbours in space, which
// makes them the sort key of whatever should be processed or stored close together.
#pragma once

#include <cstdint>

namespace glint {

// Spreads the low 10 bits of x to every third bit (bit i goes to bit 3i).
constexpr uint32_t spreadBits3(uint32_t x) {
  x &= 0x3ff;
  x = (x | (x << 16)) & 0x030000ff;
  x = (x | (x << 8)) & 0x0300f00f;
  x = (x | (x << 4)) & 0x030c30c3;
  x = (x | (x << 2)) & 0x09249249;
  return x;
}

// The 30-bit Morton code of a cell (x, y, z), each in [0, 1024): x in bit 0, y in bit 1,
// z in bit 2 of every triple.
constexpr uint32_t mortonCode3(uint32_t x, uint32_t y, uint32_t z) {
  return spreadBits3(x) | spreadBits3(y) << 1 | spreadBits3(z) << 2;
}

}  // namespace glint
