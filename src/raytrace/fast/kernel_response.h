// The kernel response G(r^2) and a hit's alpha as the BVH tracers evaluate them on the CPU
// and on the GPU: small integer powers as products and the exponential without a library
// call, so every tracer over the 8-wide BVH gets the same alphas bit for bit.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/cpu_gpu.h"
#include "math/fast_exp.h"
#include "raytrace/gaussian_kernel.h"
#include "raytrace/trace_settings.h"

namespace glint {

class KernelResponse {
 public:
  GLINT_CPU_GPU explicit KernelResponse(float power) : power_(power), exponentScale_(-1.0f / (2.0f * power)) {
    integerPower_ = (power == std::round(power) && power >= 1.0f && power <= 4.0f) ? int(power) : 0;
  }

  // kernelPower when it is 1, 2, 3 or 4, else 0.
  GLINT_CPU_GPU int integerPower() const { return integerPower_; }
  // -1 / (2 p): the response is exp(r2^p exponentScale).
  GLINT_CPU_GPU float exponentScale() const { return exponentScale_; }

  // gaussianResponse in float; small integer powers (1 and 3 are the common ones) as
  // products, within an ulp or two of powf and several times faster, and the exponential
  // inline (a libm call from AVX code measured 7% of bundled tracing with its vzeroupper).
  GLINT_CPU_GPU float operator()(float r2) const {
    float r2p;
    switch (integerPower_) {
      case 1: r2p = r2; break;
      case 2: r2p = r2 * r2; break;
      case 3: r2p = (r2 * r2) * r2; break;
      case 4: r2p = (r2 * r2) * (r2 * r2); break;
      default: return gaussianResponse(r2, power_);
    }
    return expNonPositive(r2p * exponentScale_);
  }

  // kMaxAlpha * opacity * G(r2).
  GLINT_CPU_GPU float alpha(float opacity, float r2) const { return kMaxAlpha * opacity * (*this)(r2); }

 private:
  float power_;
  float exponentScale_;
  int integerPower_;
};

}  // namespace glint
