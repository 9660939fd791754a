// Per-pixel classification of the ground truth and the error summed per kind of pixel.
#include "eval/error_breakdown.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "eval/image_metrics.h"
#include "eval/view_metrics.h"
#include "io/tonemap.h"

namespace glint {

namespace {

constexpr std::array<const char*, kPixelKindCount> kKindNames = {
    "no surface", "silhouette", "highlight edge", "flat mirror", "curved mirror", "glossy", "rough"};

void requireSize(const Image& image, const Camera& camera, int channels, const char* what) {
  if (image.width != camera.width || image.height != camera.height || image.channels != channels)
    throw Error(std::string("error breakdown: the ground truth's ") + what + " buffer does not match the view");
}

float meanChannel(const Image& image, int x, int y) {
  float sum = 0;
  for (int c = 0; c < image.channels; ++c) sum += image.at(x, y, c);
  return sum / float(image.channels);
}

// Squared differences of a and b over the pixels of one kind, every channel.
void addSquaredError(const Image& a, const Image& b, size_t pixel, double scale, MaskedError* e) {
  for (int c = 0; c < a.channels; ++c) {
    double d = double(a.pixels[pixel * a.channels + c]) - double(b.pixels[pixel * b.channels + c]);
    e->squaredError += scale * d * d;
  }
  e->values += a.channels;
}

Image tonemapped(const Image& linear) {
  Image out = linear;
  for (float& v : out.pixels) v = tonemapFilmic(v);
  return out;
}

}  // namespace

const char* pixelKindName(PixelKind kind) { return kKindNames[static_cast<int>(kind)]; }

std::vector<PixelKind> classifyPixels(const Camera& camera, const ViewBuffers& truth, const PixelKindThresholds& t) {
  const Image& depth = truth[Buffer::Depth];
  const Image& normal = truth[Buffer::Normal];
  const Image& roughness = truth[Buffer::Roughness];
  requireSize(depth, camera, 1, "depth");
  requireSize(normal, camera, 3, "normal");
  requireSize(roughness, camera, 1, "roughness");
  requireSize(truth[Buffer::Specular], camera, 3, "specular");
  const Image specular = tonemapped(truth[Buffer::Specular]);
  const int w = camera.width, h = camera.height;
  std::vector<PixelKind> kinds(size_t(w) * size_t(h), PixelKind::Rough);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      PixelKind& kind = kinds[size_t(y) * size_t(w) + size_t(x)];
      const float d = depth.at(x, y);
      if (!hasSurface(d)) {
        kind = PixelKind::NoSurface;
        continue;
      }
      const Vec3d n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      const Vec3d view = camera.generateRay(x + 0.5, y + 0.5).direction;
      bool silhouette = std::abs(dot(n, view)) < t.grazingCosine * length(view);
      bool highlightEdge = false, flat = true;
      const float s = meanChannel(specular, x, y);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const float dn = depth.at(nx, ny);
          if (!hasSurface(dn) || std::abs(dn - d) > t.depthJump * std::min(d, dn)) silhouette = true;
          if (std::abs(meanChannel(specular, nx, ny) - s) > t.highlightStep) highlightEdge = true;
        }
      // Flatness over 5x5: a large sphere's normal turns by well under a degree per pixel.
      for (int dy = -2; dy <= 2 && flat; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
          const Vec3d m(normal.at(nx, ny, 0), normal.at(nx, ny, 1), normal.at(nx, ny, 2));
          if (hasSurface(depth.at(nx, ny)) && dot(n, m) < t.flatNormalCosine) flat = false;
        }
      const float r = roughness.at(x, y);
      if (silhouette) kind = PixelKind::Silhouette;
      else if (highlightEdge) kind = PixelKind::HighlightEdge;
      else if (r < t.mirrorRoughness) kind = flat ? PixelKind::FlatMirror : PixelKind::CurvedMirror;
      else if (r < t.glossyRoughness) kind = PixelKind::Glossy;
      else kind = PixelKind::Rough;
    }
  return kinds;
}

ErrorBreakdown& ErrorBreakdown::operator+=(const ErrorBreakdown& o) {
  for (int k = 0; k < kPixelKindCount; ++k) {
    kinds[k].pixels += o.kinds[k].pixels;
    kinds[k].specular += o.kinds[k].specular;
    kinds[k].final += o.kinds[k].final;
    kinds[k].specularNoise += o.kinds[k].specularNoise;
    kinds[k].finalNoise += o.kinds[k].finalNoise;
  }
  hasNoise = hasNoise || o.hasNoise;
  return *this;
}

ErrorBreakdown breakdownView(const std::vector<PixelKind>& kinds, const ViewBuffers& rendered, const ViewBuffers& truth,
                             const ViewBuffers* halfA, const ViewBuffers* halfB) {
  const Image renderedSpecular = tonemapTo8Bit(rendered[Buffer::Specular]);
  const Image renderedFinal = tonemapTo8Bit(rendered[Buffer::Render]);
  const Image truthSpecular = tonemapTo8Bit(truth[Buffer::Specular]);
  const Image truthFinal = tonemapTo8Bit(truth[Buffer::Render]);
  if (renderedSpecular.pixels.size() != truthSpecular.pixels.size() || kinds.size() * 3 != truthSpecular.pixels.size())
    throw Error("error breakdown: the rendered view and its ground truth differ in size");
  ErrorBreakdown b;
  b.hasNoise = halfA && halfB;
  Image aSpecular, bSpecular, aFinal, bFinal;
  if (b.hasNoise) {
    // Not quantised: the noise estimate should not see the 8-bit rounding steps.
    aSpecular = tonemapped((*halfA)[Buffer::Specular]);
    bSpecular = tonemapped((*halfB)[Buffer::Specular]);
    aFinal = tonemapped((*halfA)[Buffer::Render]);
    bFinal = tonemapped((*halfB)[Buffer::Render]);
  }
  for (size_t p = 0; p < kinds.size(); ++p) {
    KindError& e = b.kinds[static_cast<int>(kinds[p])];
    ++e.pixels;
    addSquaredError(renderedSpecular, truthSpecular, p, 1.0, &e.specular);
    addSquaredError(renderedFinal, truthFinal, p, 1.0, &e.final);
    if (b.hasNoise) {
      // The mean of two independent estimates has a quarter of the variance of their
      // difference: Var((a + b)/2) = Var(a)/2 = E(a - b)^2 / 4.
      addSquaredError(aSpecular, bSpecular, p, 0.25, &e.specularNoise);
      addSquaredError(aFinal, bFinal, p, 0.25, &e.finalNoise);
    }
  }
  return b;
}

Rgb pixelKindColour(PixelKind kind) {
  switch (kind) {
    case PixelKind::NoSurface: return {0.0f, 0.0f, 0.0f};
    case PixelKind::Silhouette: return {1.0f, 0.2f, 0.2f};
    case PixelKind::HighlightEdge: return {1.0f, 0.85f, 0.1f};
    case PixelKind::FlatMirror: return {0.2f, 0.5f, 1.0f};
    case PixelKind::CurvedMirror: return {0.6f, 0.3f, 1.0f};
    case PixelKind::Glossy: return {0.2f, 0.8f, 0.4f};
    case PixelKind::Rough: return {0.45f, 0.45f, 0.45f};
    case PixelKind::Count: break;
  }
  return {1.0f, 1.0f, 1.0f};
}

Image pixelKindImage(const std::vector<PixelKind>& kinds, int width, int height) {
  if (kinds.size() != size_t(width) * size_t(height)) throw Error("error breakdown: the kind map does not match its size");
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.setRgb(x, y, pixelKindColour(kinds[size_t(y) * size_t(width) + size_t(x)]));
  return image;
}

namespace {

struct Totals {
  size_t pixels = 0;
  double specular = 0, final = 0;
};

Totals totalsOf(const ErrorBreakdown& b) {
  Totals t;
  for (const KindError& e : b.kinds) {
    t.pixels += e.pixels;
    t.specular += e.specular.squaredError;
    t.final += e.final.squaredError;
  }
  return t;
}

double share(double part, double whole) { return whole > 0 ? part / whole : NAN; }

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json toJson(const ErrorBreakdown& b) {
  const Totals t = totalsOf(b);
  nlohmann::json out = nlohmann::json::object();
  for (int k = 0; k < kPixelKindCount; ++k) {
    const KindError& e = b.kinds[k];
    nlohmann::json entry = {{"pixels", e.pixels},
                            {"pixel_share", number(share(double(e.pixels), double(t.pixels)))},
                            {"specular_error_share", number(share(e.specular.squaredError, t.specular))},
                            {"final_error_share", number(share(e.final.squaredError, t.final))},
                            {"specular_psnr_tonemapped", number(e.specular.psnr())},
                            {"final_psnr_tonemapped", number(e.final.psnr())}};
    if (b.hasNoise) {
      entry["specular_noise_share"] = number(share(e.specularNoise.squaredError, e.specular.squaredError));
      entry["final_noise_share"] = number(share(e.finalNoise.squaredError, e.final.squaredError));
    }
    out[pixelKindName(PixelKind(k))] = entry;
  }
  return out;
}

void printBreakdown(const ErrorBreakdown& b) {
  const Totals t = totalsOf(b);
  std::printf("\n%-15s %8s %9s %9s %9s %9s %9s %9s   (8-bit tonemapped; shares of the whole split's error)\n", "pixel kind",
              "pixels", "spec err", "final err", "spec dB", "final dB", "spec noise", "fin noise");
  auto percent = [](double x) {
    char text[32];
    if (!std::isfinite(x)) return std::string("-");
    std::snprintf(text, sizeof text, "%.1f%%", 100.0 * x);
    return std::string(text);
  };
  for (int k = 0; k < kPixelKindCount; ++k) {
    const KindError& e = b.kinds[k];
    if (e.pixels == 0) continue;
    std::printf("%-15s %8s %9s %9s %9s %9s %9s %9s\n", pixelKindName(PixelKind(k)),
                percent(share(double(e.pixels), double(t.pixels))).c_str(),
                percent(share(e.specular.squaredError, t.specular)).c_str(),
                percent(share(e.final.squaredError, t.final)).c_str(), formatMetric(e.specular.psnr(), 2).c_str(),
                formatMetric(e.final.psnr(), 2).c_str(),
                b.hasNoise ? percent(share(e.specularNoise.squaredError, e.specular.squaredError)).c_str() : "-",
                b.hasNoise ? percent(share(e.finalNoise.squaredError, e.final.squaredError)).c_str() : "-");
  }
  if (b.hasNoise)
    std::printf("(noise: the part of a kind's squared error expected from Monte Carlo noise of the render alone, from "
                "two independent halves of its samples)\n");
}

}  // namespace glint
