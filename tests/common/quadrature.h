// Adaptive numerical integration for tests: 1D Simpson and 2D Gauss-Legendre over rectangles.
#pragma once

#include <cmath>

namespace glint::test {

namespace detail {

template <typename F>
double simpsonStep(const F& f, double a, double b, double fa, double fm, double fb, double whole, double tolerance,
                   int depth, int minDepth) {
  double m = 0.5 * (a + b);
  double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  double flm = f(lm), frm = f(rm);
  double left = (m - a) / 6 * (fa + 4 * flm + fm);
  double right = (b - m) / 6 * (fm + 4 * frm + fb);
  double delta = left + right - whole;
  // Lyness 1969: the difference estimates 15x the error of the refined estimate, and
  // adding delta / 15 is one Richardson extrapolation step.
  if (depth >= minDepth && (depth >= 50 || std::abs(delta) <= 15 * tolerance)) return left + right + delta / 15;
  return simpsonStep(f, a, m, fa, flm, fm, left, tolerance / 2, depth + 1, minDepth) +
         simpsonStep(f, m, b, fm, frm, fb, right, tolerance / 2, depth + 1, minDepth);
}

// 4-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4).
constexpr double kGaussNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kGaussWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

template <typename F>
double gaussLegendre4x4(const F& f, double x0, double x1, double y0, double y1) {
  double hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0);
  double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  double sum = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      sum += kGaussWeights[i] * kGaussWeights[j] * f(cx + hx * kGaussNodes[i], cy + hy * kGaussNodes[j]);
  return sum * hx * hy;
}

template <typename F>
double rectStep(const F& f, double x0, double x1, double y0, double y1, double whole, double tolerance, int depthLeft,
                int minDepthLeft) {
  double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
  double q[4] = {gaussLegendre4x4(f, x0, xm, y0, ym), gaussLegendre4x4(f, xm, x1, y0, ym),
                 gaussLegendre4x4(f, x0, xm, ym, y1), gaussLegendre4x4(f, xm, x1, ym, y1)};
  double sum = q[0] + q[1] + q[2] + q[3];
  if (depthLeft <= 0 || (minDepthLeft <= 0 && std::abs(sum - whole) <= tolerance)) return sum;
  return rectStep(f, x0, xm, y0, ym, q[0], tolerance / 2, depthLeft - 1, minDepthLeft - 1) +
         rectStep(f, xm, x1, y0, ym, q[1], tolerance / 2, depthLeft - 1, minDepthLeft - 1) +
         rectStep(f, x0, xm, ym, y1, q[2], tolerance / 2, depthLeft - 1, minDepthLeft - 1) +
         rectStep(f, xm, x1, ym, y1, q[3], tolerance / 2, depthLeft - 1, minDepthLeft - 1);
}

}  // namespace detail

// Integral of f(x) over [a, b] by adaptive Simpson. minDepth forces that many halvings
// before the error test, so a narrow peak between the first few nodes is not missed.
template <typename F>
double integrate1D(const F& f, double a, double b, double tolerance, int minDepth = 4) {
  double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  double whole = (b - a) / 6 * (fa + 4 * fm + fb);
  return detail::simpsonStep(f, a, b, fa, fm, fb, whole, tolerance, 0, minDepth);
}

// Integral of f(x, y) over [x0, x1] x [y0, y1]: split into nx x ny cells first, then refine
// each cell into quadrants until the 4x4 Gauss-Legendre estimates of a cell and of its
// quadrants agree within the cell's share of tolerance (or maxDepth levels are used up).
// The first minDepth levels are always refined: two estimates that both miss a narrow
// feature agree, so without them a peak or a sliver of support between nodes goes unseen.
template <typename F>
double integrateRect(const F& f, double x0, double x1, double y0, double y1, double tolerance, int nx = 1, int ny = 1,
                     int minDepth = 2, int maxDepth = 8) {
  double sum = 0;
  double cellTolerance = tolerance / (nx * ny);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      double a0 = x0 + (x1 - x0) * i / nx, a1 = x0 + (x1 - x0) * (i + 1) / nx;
      double b0 = y0 + (y1 - y0) * j / ny, b1 = y0 + (y1 - y0) * (j + 1) / ny;
      double whole = detail::gaussLegendre4x4(f, a0, a1, b0, b1);
      sum += detail::rectStep(f, a0, a1, b0, b1, whole, cellTolerance, maxDepth, minDepth);
    }
  }
  return sum;
}

}  // namespace glint::test
