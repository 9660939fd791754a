// The 8-lane tests of the 8-wide BVH (the scalar ones run on the GPU too): a ray against the 8 child boxes of a node (slab test),
// against the 8 Gaussians of a leaf block, and a Gaussian against a packet of 8 rays (the
// proxy part of evaluateGaussian in gaussian_kernel.h). Each has an AVX2 version and a scalar one that performs the same
// float operations in the same order (explicit fused multiply-adds), so both give
// bit-identical results.
#pragma once

#include <cmath>
#include <cstdint>

#ifdef __AVX2__
#include <immintrin.h>
#endif

#include "core/cpu_gpu.h"
#include "raytrace/fast/bvh8.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {

// Per-ray constants of the tests.
struct Bvh8Ray {
  float origin[3];
  float direction[3];
  float invDirection[3];     // 1 / d, with zero components replaced by +-1e-20 (no NaN)
  float originOverDir[3];    // origin * invDirection
  int nearPlane[3];          // Bvh8Node::bounds row of the entry plane per axis
  int farPlane[3];
  float tMin;

  GLINT_CPU_GPU explicit Bvh8Ray(const TraceRay& ray) {
    // Normalised again (as the reference tracer does), so distances are lengths.
    Vec3f d = normalize(ray.direction);
    for (int a = 0; a < 3; ++a) {
      origin[a] = ray.origin[a];
      direction[a] = d[a];
      float safe = std::abs(direction[a]) > 1e-20f ? direction[a] : std::copysign(1e-20f, direction[a]);
      invDirection[a] = 1.0f / safe;
      originOverDir[a] = origin[a] * invDirection[a];
      nearPlane[a] = 2 * a + (invDirection[a] < 0.0f ? 1 : 0);
      farPlane[a] = 2 * a + (invDirection[a] < 0.0f ? 0 : 1);
    }
    tMin = ray.tMin;
  }
};

// Per lane of a block (or of a ray packet): closest approach tPeak, half chord length through the proxy,
// squared local distance r2 and local point (meaningful in the lanes that pass).
struct Bvh8BlockCandidates {
  alignas(32) float tPeak[kBvhWidth];
  alignas(32) float half[kBvhWidth];
  alignas(32) float r2[kBvhWidth];
  alignas(32) float localPoint[3][kBvhWidth];
};

// Child boxes hit in [tMin, inf): returns the lane mask and each lane's entry distance
// max(box entry, tMin) (and, when tFar is given, its exit distance).
GLINT_CPU_GPU inline uint32_t intersectNodeScalar(const Bvh8Node& node, const Bvh8Ray& ray, float tNear[kBvhWidth],
                                                  float* tFar = nullptr) {
  uint32_t mask = 0;
  GLINT_UNROLL
  for (int c = 0; c < kBvhWidth; ++c) {
    float n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = std::fma(node.bounds[ray.nearPlane[a]][c], ray.invDirection[a], -ray.originOverDir[a]);
      f[a] = std::fma(node.bounds[ray.farPlane[a]][c], ray.invDirection[a], -ray.originOverDir[a]);
    }
    // Same operand order as the AVX2 max/min below.
    float tn = std::max(std::max(n[0], n[1]), std::max(n[2], ray.tMin));
    float tf = std::min(std::min(f[0], f[1]), f[2]);
    tNear[c] = tn;
    if (tFar) tFar[c] = tf;
    if (tn <= tf) mask |= 1u << c;
  }
  return mask;
}

// A bundle's rays in packets of 8, one ray per lane: they share the bundle's origin, so a
// Gaussian can be tested against 8 rays at once (intersectPacket) as a ray is against 8
// Gaussians (intersectBlock).
struct alignas(32) RayPacket {
  float direction[3][kBvhWidth];  // normalised, as Bvh8Ray's
  float tMin[kBvhWidth];
};

// The proxy test of evaluateGaussian for one (Gaussian, ray) pair: Gaussian `g` of `block`,
// ray (o, d, tMin) with d unit length; writes lane `i` of *out and returns whether it passes.
// Both the block and the packet tests use it, so they agree bit for bit.
GLINT_CPU_GPU inline bool proxyTestScalar(const Bvh8Block& block, int g, const float o[3], const float d[3], float tMin,
                            Bvh8BlockCandidates* out, int i) {
  // Move the origin to the ray's closest point to the mean (world space) first.
  float dox = o[0] - block.mean[0][g], doy = o[1] - block.mean[1][g], doz = o[2] - block.mean[2][g];
  float t0 = -std::fma(doz, d[2], std::fma(doy, d[1], dox * d[0]));
  float w[3] = {std::fma(d[0], t0, dox), std::fma(d[1], t0, doy), std::fma(d[2], t0, doz)};
  float oL[3], dL[3];
  for (int r = 0; r < 3; ++r) {
    const float m0 = block.worldToLocal[3 * r][g], m1 = block.worldToLocal[3 * r + 1][g],
                m2 = block.worldToLocal[3 * r + 2][g];
    oL[r] = std::fma(m2, w[2], std::fma(m1, w[1], m0 * w[0]));
    dL[r] = std::fma(m2, d[2], std::fma(m1, d[1], m0 * d[0]));
  }
  float dd = std::fma(dL[2], dL[2], std::fma(dL[1], dL[1], dL[0] * dL[0]));
  float od = std::fma(oL[2], dL[2], std::fma(oL[1], dL[1], oL[0] * dL[0]));
  // One division serves both quotients by dd: it sits on the test's critical path.
  float invDd = 1.0f / dd;
  float tc = -(od * invDd);
  float p[3] = {std::fma(dL[0], tc, oL[0]), std::fma(dL[1], tc, oL[1]), std::fma(dL[2], tc, oL[2])};
  float r2 = std::fma(p[2], p[2], std::fma(p[1], p[1], p[0] * p[0]));
  float R2 = block.radius2[g];
  float half = std::sqrt((R2 - r2) * invDd);
  float tPeak = t0 + tc;
  float tExit = tPeak + half;
  out->tPeak[i] = tPeak;
  out->half[i] = half;
  out->r2[i] = r2;
  for (int r = 0; r < 3; ++r) out->localPoint[r][i] = p[r];
  return r2 <= R2 && dd > 0.0f && tExit >= tMin;
}

// The proxy test for the 8 Gaussians of a block and one ray; returns the mask of lanes
// that pass.
GLINT_CPU_GPU inline uint32_t intersectBlockScalar(const Bvh8Block& block, const Bvh8Ray& ray, Bvh8BlockCandidates* out) {
  uint32_t mask = 0;
  for (int i = 0; i < kBvhWidth; ++i)
    mask |= uint32_t(proxyTestScalar(block, i, ray.origin, ray.direction, ray.tMin, out, i)) << i;
  return mask;
}

// The proxy test for Gaussian g of a block and the 8 rays of a packet (origin shared);
// returns the mask of rays that pass, their results in the lanes of *out.
inline uint32_t intersectPacketScalar(const Bvh8Block& block, int g, const float origin[3], const RayPacket& packet,
                                      Bvh8BlockCandidates* out) {
  uint32_t mask = 0;
  for (int i = 0; i < kBvhWidth; ++i) {
    float d[3] = {packet.direction[0][i], packet.direction[1][i], packet.direction[2][i]};
    mask |= uint32_t(proxyTestScalar(block, g, origin, d, packet.tMin[i], out, i)) << i;
  }
  return mask;
}

#ifdef __AVX2__
inline uint32_t intersectNodeAvx2(const Bvh8Node& node, const Bvh8Ray& ray, float tNear[kBvhWidth]) {
  __m256 n[3], f[3];
  for (int a = 0; a < 3; ++a) {
    __m256 inv = _mm256_set1_ps(ray.invDirection[a]);
    __m256 oInv = _mm256_set1_ps(ray.originOverDir[a]);
    n[a] = _mm256_fmsub_ps(_mm256_load_ps(node.bounds[ray.nearPlane[a]]), inv, oInv);
    f[a] = _mm256_fmsub_ps(_mm256_load_ps(node.bounds[ray.farPlane[a]]), inv, oInv);
  }
  __m256 tn = _mm256_max_ps(_mm256_max_ps(n[0], n[1]), _mm256_max_ps(n[2], _mm256_set1_ps(ray.tMin)));
  __m256 tf = _mm256_min_ps(_mm256_min_ps(f[0], f[1]), f[2]);
  _mm256_storeu_ps(tNear, tn);
  return uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ)));
}

// proxyTestScalar on 8 lanes: the Gaussian's mean, frame and proxy radius and the ray's
// origin, direction and tMin, each either loaded per lane or broadcast.
inline uint32_t proxyTestAvx2(const __m256 mean[3], const __m256 m[9], __m256 R2, const __m256 o[3], const __m256 d[3],
                              __m256 tMin, Bvh8BlockCandidates* out) {
  const __m256 signBit = _mm256_set1_ps(-0.0f);
  // Move the origin to the ray's closest point to the mean (world space) first.
  __m256 dox = _mm256_sub_ps(o[0], mean[0]), doy = _mm256_sub_ps(o[1], mean[1]), doz = _mm256_sub_ps(o[2], mean[2]);
  __m256 t0 = _mm256_xor_ps(_mm256_fmadd_ps(doz, d[2], _mm256_fmadd_ps(doy, d[1], _mm256_mul_ps(dox, d[0]))), signBit);
  __m256 w0 = _mm256_fmadd_ps(d[0], t0, dox), w1 = _mm256_fmadd_ps(d[1], t0, doy), w2 = _mm256_fmadd_ps(d[2], t0, doz);
  __m256 oL[3], dL[3];
  for (int r = 0; r < 3; ++r) {
    const __m256 m0 = m[3 * r], m1 = m[3 * r + 1], m2 = m[3 * r + 2];
    oL[r] = _mm256_fmadd_ps(m2, w2, _mm256_fmadd_ps(m1, w1, _mm256_mul_ps(m0, w0)));
    dL[r] = _mm256_fmadd_ps(m2, d[2], _mm256_fmadd_ps(m1, d[1], _mm256_mul_ps(m0, d[0])));
  }
  __m256 dd = _mm256_fmadd_ps(dL[2], dL[2], _mm256_fmadd_ps(dL[1], dL[1], _mm256_mul_ps(dL[0], dL[0])));
  __m256 od = _mm256_fmadd_ps(oL[2], dL[2], _mm256_fmadd_ps(oL[1], dL[1], _mm256_mul_ps(oL[0], dL[0])));
  __m256 invDd = _mm256_div_ps(_mm256_set1_ps(1.0f), dd);
  __m256 tc = _mm256_xor_ps(_mm256_mul_ps(od, invDd), signBit);
  __m256 p0 = _mm256_fmadd_ps(dL[0], tc, oL[0]), p1 = _mm256_fmadd_ps(dL[1], tc, oL[1]),
         p2 = _mm256_fmadd_ps(dL[2], tc, oL[2]);
  __m256 r2 = _mm256_fmadd_ps(p2, p2, _mm256_fmadd_ps(p1, p1, _mm256_mul_ps(p0, p0)));
  __m256 inside = _mm256_and_ps(_mm256_cmp_ps(r2, R2, _CMP_LE_OQ), _mm256_cmp_ps(dd, _mm256_setzero_ps(), _CMP_GT_OQ));
  uint32_t mask = uint32_t(_mm256_movemask_ps(inside));
  __m256 half = _mm256_sqrt_ps(_mm256_mul_ps(_mm256_sub_ps(R2, r2), invDd));
  __m256 tPeak = _mm256_add_ps(t0, tc);
  __m256 tExit = _mm256_add_ps(tPeak, half);
  mask &= uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(tExit, tMin, _CMP_GE_OQ)));
  _mm256_store_ps(out->tPeak, tPeak);
  _mm256_store_ps(out->half, half);
  _mm256_store_ps(out->r2, r2);
  _mm256_store_ps(out->localPoint[0], p0);
  _mm256_store_ps(out->localPoint[1], p1);
  _mm256_store_ps(out->localPoint[2], p2);
  return mask;
}

inline uint32_t intersectBlockAvx2(const Bvh8Block& block, const Bvh8Ray& ray, Bvh8BlockCandidates* out) {
  __m256 mean[3], m[9], o[3], d[3];
  for (int a = 0; a < 3; ++a) {
    mean[a] = _mm256_load_ps(block.mean[a]);
    o[a] = _mm256_set1_ps(ray.origin[a]);
    d[a] = _mm256_set1_ps(ray.direction[a]);
  }
  for (int k = 0; k < 9; ++k) m[k] = _mm256_load_ps(block.worldToLocal[k]);
  return proxyTestAvx2(mean, m, _mm256_load_ps(block.radius2), o, d, _mm256_set1_ps(ray.tMin), out);
}

inline uint32_t intersectPacketAvx2(const Bvh8Block& block, int g, const float origin[3], const RayPacket& packet,
                                    Bvh8BlockCandidates* out) {
  __m256 mean[3], m[9], o[3], d[3];
  for (int a = 0; a < 3; ++a) {
    mean[a] = _mm256_set1_ps(block.mean[a][g]);
    o[a] = _mm256_set1_ps(origin[a]);
    d[a] = _mm256_load_ps(packet.direction[a]);
  }
  for (int k = 0; k < 9; ++k) m[k] = _mm256_set1_ps(block.worldToLocal[k][g]);
  return proxyTestAvx2(mean, m, _mm256_set1_ps(block.radius2[g]), o, d, _mm256_load_ps(packet.tMin), out);
}
#endif

inline uint32_t intersectNode(const Bvh8Node& node, const Bvh8Ray& ray, float tNear[kBvhWidth]) {
#ifdef __AVX2__
  return intersectNodeAvx2(node, ray, tNear);
#else
  return intersectNodeScalar(node, ray, tNear);
#endif
}

inline uint32_t intersectBlock(const Bvh8Block& block, const Bvh8Ray& ray, Bvh8BlockCandidates* out) {
#ifdef __AVX2__
  return intersectBlockAvx2(block, ray, out);
#else
  return intersectBlockScalar(block, ray, out);
#endif
}

inline uint32_t intersectPacket(const Bvh8Block& block, int g, const float origin[3], const RayPacket& packet,
                                Bvh8BlockCandidates* out) {
#ifdef __AVX2__
  return intersectPacketAvx2(block, g, origin, packet, out);
#else
  return intersectPacketScalar(block, g, origin, packet, out);
#endif
}

}  // namespace glint
