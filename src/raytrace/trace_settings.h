// Settings of Gaussian ray tracing shared by every tracer (fast, Embree baseline, reference).
#pragma once

namespace glint {

struct TraceSettings {
  // Generalised Gaussian exponent p of the response G = exp(-(r^2)^p / (2p)); 1 is the
  // ordinary Gaussian, 3 the paper's code default. 2 blends the constant normals of
  // neighbouring Gaussians more smoothly, so reflected rays turn less at Gaussian borders:
  // on builtin:spheres specular rose from 25.36 to 25.92 dB and the chrome spheres' median
  // normal error fell from 1.03 to 0.85 degrees (README, Training with reflections).
  float kernelPower = 2.0f;
  // Hits whose alpha = kMaxAlpha * opacity * G is below this are ignored; it also sets
  // the proxy: the ellipsoid where alpha reaches alphaMin bounds every hit that counts.
  float alphaMin = 0.005f;
  // Compositing stops once the transmittance falls below this.
  float minTransmittance = 0.01f;
  // After termination, keep traversing to get the exact final transmittance T_f of all
  // hits for the truncation tail estimate of appendix A.2; when false, traversal stops at
  // termination (fastest) and the estimate takes the tail as opaque (T_f = 0).
  bool exactTail = false;
};

// Alpha never reaches 1, so transmittance never becomes exactly 0 (3DGS convention).
constexpr float kMaxAlpha = 0.9999f;

}  // namespace glint
