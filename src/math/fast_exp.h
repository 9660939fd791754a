// e^x in float without a library call: the fast tracer evaluates it for every kernel
// response, from AVX code, where a call to expf also costs the vzeroupper before it.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/cpu_gpu.h"

#ifdef __AVX2__
#include <immintrin.h>
#endif

namespace glint {

namespace fast_exp {
constexpr float kLog2e = 1.44269504088896341f;
constexpr float kLn2Hi = 0.693145751953125f;  // ln 2 with the low 12 bits of its mantissa zero: n ln2Hi is exact
constexpr float kLn2Lo = 1.42860682030941723e-6f;
// Taylor coefficient k of e^r from r^7 (k = 0) down to r^0 (k = 7), for Horner's scheme. A
// function, not an array: GPU code cannot read a host array.
constexpr float taylor(int k) {
  constexpr float inverseFactorial[8] = {1.0f / 5040.0f, 1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f,
                                         1.0f / 6.0f,    0.5f,          1.0f,          1.0f};
  return inverseFactorial[k];
}
}  // namespace fast_exp

// e^x for x <= 0, within 1 ulp of the exact value for x >= -87 (where the result is a
// normal float), and 0 below. Cody-Waite reduction x = n ln2 + r, |r| <= ln2 / 2, then the
// degree-7 Taylor polynomial of e^r (truncation error r^8 / 8! below 5e-9 relative; degree
// 6 measured 2.6 ulp), and the scale 2^n put into the exponent bits.
GLINT_CPU_GPU inline float expNonPositive(float x) {
  using namespace fast_exp;
  if (!(x >= -87.0f)) return 0.0f;
  float n = std::floor(std::fma(x, kLog2e, 0.5f));
  float r = std::fma(n, -kLn2Hi, x);
  r = std::fma(n, -kLn2Lo, r);
  float p = taylor(0);
  for (int k = 1; k < 8; ++k) p = std::fma(p, r, taylor(k));
  float scale = std::bit_cast<float>(uint32_t(int32_t(n) + 127) << 23);
  return p * scale;
}

#ifdef __AVX2__
// expNonPositive on 8 lanes, with the same operations: bit for bit the scalar result.
inline __m256 expNonPositiveAvx2(__m256 x) {
  using namespace fast_exp;
  __m256 inRange = _mm256_cmp_ps(x, _mm256_set1_ps(-87.0f), _CMP_GE_OQ);
  __m256 n = _mm256_floor_ps(_mm256_fmadd_ps(x, _mm256_set1_ps(kLog2e), _mm256_set1_ps(0.5f)));
  __m256 r = _mm256_fmadd_ps(n, _mm256_set1_ps(-kLn2Hi), x);
  r = _mm256_fmadd_ps(n, _mm256_set1_ps(-kLn2Lo), r);
  __m256 p = _mm256_set1_ps(taylor(0));
  for (int k = 1; k < 8; ++k) p = _mm256_fmadd_ps(p, r, _mm256_set1_ps(taylor(k)));
  __m256i exponent = _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvttps_epi32(n), _mm256_set1_epi32(127)), 23);
  return _mm256_and_ps(_mm256_mul_ps(p, _mm256_castsi256_ps(exponent)), inRange);
}
#endif

}  // namespace glint
