// Windows of directions binned in (cos theta, phi), with quadrature of densities per cell.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include "common/quadrature.h"
#include "math/vec.h"

namespace glint::test {

constexpr double kTwoPi = 2 * std::numbers::pi;

// A grid over a window of directions: cos(theta) in [zMin, zMax] split into thetaCells
// rings and phi in [phiStart, phiStart + phiExtent) into phiCells sectors, plus one last
// cell for every direction outside the window. Cells are equal in (cos theta, phi), which
// is also equal in solid angle since d(omega) = d(cos theta) d(phi); a density over solid
// angle is therefore also the density over this parameter rectangle. A window fitted to
// a narrow lobe spreads its samples over many cells instead of one or two. The pole is
// always the shading normal, so the horizon (where reflection densities jump to zero) is
// a cell boundary and never cuts through a cell the quadrature would have to resolve.
struct DirectionGrid {
  int thetaCells = 10;
  int phiCells = 20;
  double zMin = 0.0;  // 0 for the upper hemisphere, -1 for the whole sphere
  double zMax = 1.0;
  double phiStart = 0.0;
  double phiExtent = kTwoPi;

  static DirectionGrid hemisphere(int thetaCells = 10, int phiCells = 20) { return {thetaCells, phiCells, 0.0}; }
  static DirectionGrid sphere() { return {20, 20, -1.0}; }
  // The window of the upper hemisphere holding every direction within angle radius of axis.
  static DirectionGrid around(const Vec3f& axis, double radius, int thetaCells = 10, int phiCells = 20) {
    Vec3d a = normalize(Vec3d(axis));
    double theta = std::acos(std::clamp(a.z, -1.0, 1.0));
    DirectionGrid grid{thetaCells, phiCells};
    grid.zMin = std::max(0.0, std::cos(std::min(std::numbers::pi, theta + radius)));
    grid.zMax = std::cos(std::max(0.0, theta - radius));
    if (theta > radius && theta + radius < std::numbers::pi) {  // the cap holds neither pole
      // Largest azimuth difference within a cap of angular radius r centred at colatitude theta.
      double halfExtent = std::asin(std::min(1.0, std::sin(radius) / std::sin(theta)));
      grid.phiStart = std::atan2(a.y, a.x) - halfExtent;
      grid.phiExtent = 2 * halfExtent;
    }
    return grid;
  }

  // Cells of the window plus the one outside it.
  int cellCount() const { return thetaCells * phiCells + 1; }
  int outsideCell() const { return thetaCells * phiCells; }

  int cellOf(const Vec3f& w) const {
    double z = std::clamp(double(w.z), -1.0, 1.0);
    double phi = std::remainder(std::atan2(double(w.y), double(w.x)) - phiStart, kTwoPi);  // in [-pi, pi]
    if (phi < 0) phi += kTwoPi;
    if (z < zMin || z > zMax || phi >= phiExtent) return outsideCell();
    int i = std::min(int((z - zMin) / (zMax - zMin) * thetaCells), thetaCells - 1);
    int j = std::min(int(phi / phiExtent * phiCells), phiCells - 1);
    return i * phiCells + j;
  }

  static Vec3f direction(double z, double phi) {
    double r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3f(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }

  // The integral of pdf (a density over solid angle) over each cell, each within about tolerance.
  std::vector<double> cellIntegrals(const std::function<double(const Vec3f&)>& pdf, double tolerance) const {
    std::vector<double> integrals(cellCount(), 0.0);
    auto integrand = [&](double z, double phi) { return pdf(direction(z, phi)); };
    for (int i = 0; i < thetaCells; ++i) {
      double z0 = zMin + (zMax - zMin) * i / thetaCells, z1 = zMin + (zMax - zMin) * (i + 1) / thetaCells;
      for (int j = 0; j < phiCells; ++j) {
        double phi0 = phiStart + phiExtent * j / phiCells, phi1 = phiStart + phiExtent * (j + 1) / phiCells;
        integrals[i * phiCells + j] = integrateRect(integrand, z0, z1, phi0, phi1, tolerance);
      }
    }
    // The outside: the bands below and above the window and the rest of the window's band,
    // each split at the horizon so that no rectangle straddles it.
    double outside = 0;
    auto addBand = [&](double z0, double z1, double phi0, double phi1) {
      if (z1 <= z0 || phi1 <= phi0) return;
      for (auto [a, b] : {std::pair(z0, std::min(z1, 0.0)), std::pair(std::max(z0, 0.0), z1)})
        if (b > a) outside += integrateRect(integrand, a, b, phi0, phi1, tolerance, thetaCells, phiCells);
    };
    addBand(-1, zMin, 0, kTwoPi);
    addBand(zMax, 1, 0, kTwoPi);
    addBand(zMin, zMax, phiStart + phiExtent, phiStart + kTwoPi);
    integrals[outsideCell()] = outside;
    return integrals;
  }

  // The integral of f over the whole sphere of directions.
  double integrate(const std::function<double(const Vec3f&)>& f, double tolerance = 1e-7) const {
    std::vector<double> integrals = cellIntegrals(f, tolerance / cellCount());
    return std::accumulate(integrals.begin(), integrals.end(), 0.0);
  }

  // sampleCount times the integral of pdf over each cell. The quadrature aims for an error
  // well below one sample per cell, far under the Poisson noise of the counts.
  std::vector<double> expectedCounts(const std::function<double(const Vec3f&)>& pdf, double sampleCount) const {
    std::vector<double> expected = cellIntegrals(pdf, 0.02 / sampleCount);
    for (double& e : expected) e = sampleCount * std::max(e, 0.0);
    return expected;
  }
};

}  // namespace glint::test
