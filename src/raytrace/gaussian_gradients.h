// Per-Gaussian gradient accumulators in structure-of-arrays form, one per parameter array
// of GaussianScene, plus the blend weight each Gaussian received (for weight pruning).
#pragma once

#include <cstddef>
#include <vector>

#include "math/quat.h"
#include "math/vec.h"

namespace glint {

// What the backward pass of one ray gives one of its hits (derivations D11-D12).
template <typename T>
struct HitGradient {
  Vec3<T> v_position;
  Quat<T> v_rotation{0, 0, 0, 0};
  Vec3<T> v_logScale;
  T v_opacityLogit = 0;
  Vec3<T> v_diffuse;
  Vec3<T> v_normal;
  T v_roughness = 0;
  Vec3<T> v_f0;
  T weight = 0;  // the hit's blend weight w_i = T_i alpha_i (not a gradient)
};

struct GaussianGradients {
  std::vector<Vec3f> position;
  std::vector<Quatf> rotation;  // adjoint of the stored (unnormalised) quaternion
  std::vector<Vec3f> logScale;
  std::vector<float> opacityLogit;
  std::vector<Rgb> diffuse;
  std::vector<Vec3f> normal;
  std::vector<float> roughness;
  std::vector<Rgb> f0;
  std::vector<float> weight;  // accumulated blend weight

  size_t size() const { return position.size(); }
  // Resizes to n Gaussians and zeroes everything.
  void reset(size_t n);
  // Resizes to n >= size() Gaussians, keeping the existing entries; new entries are zero.
  void grow(size_t n);
  // Zeroes the entries [begin, end) (so that parallel loops can clear their own ranges).
  void zero(size_t begin, size_t end);

  template <typename T>
  void add(size_t i, const HitGradient<T>& g) {
    position[i] += Vec3f(g.v_position);
    rotation[i].w += float(g.v_rotation.w);
    rotation[i].x += float(g.v_rotation.x);
    rotation[i].y += float(g.v_rotation.y);
    rotation[i].z += float(g.v_rotation.z);
    logScale[i] += Vec3f(g.v_logScale);
    opacityLogit[i] += float(g.v_opacityLogit);
    diffuse[i] += Rgb(g.v_diffuse);
    normal[i] += Vec3f(g.v_normal);
    roughness[i] += float(g.v_roughness);
    f0[i] += Rgb(g.v_f0);
    weight[i] += float(g.weight);
  }

  // Adds the entries [begin, end) of other into this (reduction of per-thread buffers).
  void addRange(const GaussianGradients& other, size_t begin, size_t end);
};

}  // namespace glint
