// Orthonormal frames: local shading coordinates with the normal as +z.
#pragma once

#include <cmath>

#include "core/cpu_gpu.h"
#include "math/vec.h"

namespace glint {

template <typename T>
struct Frame {
  Vec3<T> s, t, n;  // tangent, bitangent, normal

  // Builds a frame around a unit normal without branches on its direction.
  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1).
  GLINT_CPU_GPU static Frame fromNormal(const Vec3<T>& n) {
    T sign = std::copysign(T(1), n.z);
    T a = T(-1) / (sign + n.z);
    T b = n.x * n.y * a;
    Frame f;
    f.s = {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
    f.t = {b, sign + n.y * n.y * a, -n.y};
    f.n = n;
    return f;
  }

  GLINT_CPU_GPU Vec3<T> toLocal(const Vec3<T>& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  GLINT_CPU_GPU Vec3<T> toWorld(const Vec3<T>& v) const { return s * v.x + t * v.y + n * v.z; }
};

using Framef = Frame<float>;
using Framed = Frame<double>;

}  // namespace glint
