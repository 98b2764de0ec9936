// IEEE 754 binary16 ("half") conversions on the host, for texels the device reads with
// vload_half (kernels/texture.cl): float -> half rounds to nearest, ties to even; overflow gives
// infinity, NaN stays NaN.
#pragma once

#include <cstdint>
#include <cstring>

namespace clpt {

inline uint16_t float_to_half_bits(float value) {
  uint32_t f;
  std::memcpy(&f, &value, 4);
  const uint32_t sign = (f >> 16) & 0x8000u;
  const uint32_t abs = f & 0x7fffffffu;
  if (abs >= 0x7f800000u) return uint16_t(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));  // inf, NaN
  if (abs >= 0x477ff000u) return uint16_t(sign | 0x7c00u);  // rounds past 65504: infinity
  if (abs < 0x38800000u) {  // a half subnormal (or zero): units of 2^-24
    if (abs < 0x33000000u) return uint16_t(sign);  // below half of 2^-24
    const uint32_t mantissa = (abs & 0x7fffffu) | 0x800000u;
    const int shift = 126 - int(abs >> 23);  // 14 .. 24
    const uint32_t half = mantissa >> shift;
    const uint32_t rest = mantissa & ((1u << shift) - 1u), halfway = 1u << (shift - 1);
    return uint16_t(sign | (half + (rest > halfway || (rest == halfway && (half & 1u)) ? 1u : 0u)));
  }
  const uint32_t rebased = abs - 0x38000000u;  // exponent 127 -> 15
  const uint32_t half = rebased >> 13, rest = rebased & 0x1fffu;
  return uint16_t(sign | (half + (rest > 0x1000u || (rest == 0x1000u && (half & 1u)) ? 1u : 0u)));
}

inline float half_bits_to_float(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000u) << 16;
  const uint32_t exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  uint32_t f;
  if (exponent == 0) {
    if (mantissa == 0) {
      f = sign;
    } else {  // subnormal: normalise
      int e = -1;
      uint32_t m = mantissa;
      do {
        ++e;
        m <<= 1;
      } while (!(m & 0x400u));
      f = sign | uint32_t(127 - 15 - e) << 23 | (m & 0x3ffu) << 13;
    }
  } else if (exponent == 31) {
    f = sign | 0x7f800000u | mantissa << 13;
  } else {
    f = sign | (exponent + 112u) << 23 | mantissa << 13;
  }
  float out;
  std::memcpy(&out, &f, 4);
  return out;
}

}  // namespace clpt
