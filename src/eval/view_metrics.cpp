// Evaluation of one view against its ground truth, averaging over views, and JSON output.
#include "eval/view_metrics.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "eval/image_metrics.h"

namespace glint {

namespace {

// Mean of the finite values of one metric; see averageViewMetrics for the other cases.
template <typename Get>
double meanOfFinite(std::span<const ViewMetrics> views, Get get) {
  double sum = 0;
  size_t count = 0;
  bool anyInfinite = false;
  for (const ViewMetrics& v : views) {
    double x = get(v);
    if (std::isfinite(x)) {
      sum += x;
      ++count;
    } else if (std::isinf(x)) {
      anyInfinite = true;
    }
  }
  if (count > 0) return sum / double(count);
  return anyInfinite ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
}

PassMetrics averagePass(std::span<const ViewMetrics> views, PassMetrics ViewMetrics::* pass) {
  PassMetrics m;
  m.psnr = meanOfFinite(views, [&](const ViewMetrics& v) { return (v.*pass).psnr; });
  m.ssim = meanOfFinite(views, [&](const ViewMetrics& v) { return (v.*pass).ssim; });
  m.psnrTonemapped = meanOfFinite(views, [&](const ViewMetrics& v) { return (v.*pass).psnrTonemapped; });
  m.ssimTonemapped = meanOfFinite(views, [&](const ViewMetrics& v) { return (v.*pass).ssimTonemapped; });
  return m;
}

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json passJson(const PassMetrics& m) {
  return {{"psnr", number(m.psnr)},
          {"ssim", number(m.ssim)},
          {"psnr_tonemapped", number(m.psnrTonemapped)},
          {"ssim_tonemapped", number(m.ssimTonemapped)}};
}

// A number, or NaN for null (how toJson stores NaN and infinity).
double numberAt(const nlohmann::json& j, const char* key, const std::string& file, const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    throw Error(file, "key \"" + where + "." + key + "\" is missing");
  const nlohmann::json& v = j[key];
  if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!v.is_number()) throw Error(file, "key \"" + where + "." + key + "\" is not a number");
  return v.get<double>();
}

PassMetrics passFromJson(const nlohmann::json& j, const char* pass, const std::string& file,
                         const std::string& where) {
  if (!j.contains(pass) || !j[pass].is_object())
    throw Error(file, "key \"" + where + "." + pass + "\" is missing or not an object");
  const nlohmann::json& p = j[pass];
  const std::string at = where + "." + pass;
  return {numberAt(p, "psnr", file, at), numberAt(p, "ssim", file, at), numberAt(p, "psnr_tonemapped", file, at),
          numberAt(p, "ssim_tonemapped", file, at)};
}

}  // namespace

PassMetrics evaluatePass(const Image& predicted, const Image& truth, Transfer display) {
  return {psnr(predicted, truth), ssim(predicted, truth), psnrTonemapped8Bit(predicted, truth, display),
          ssimTonemapped8Bit(predicted, truth, display)};
}

ViewMetrics evaluateView(const ViewBuffers& rendered, const ViewBuffers& truth, Transfer display) {
  // A capture's view may lack ground truth for some buffers: their metrics have no value.
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  auto pass = [&](Buffer b) {
    return truth[b].empty() ? PassMetrics{kNone, kNone, kNone, kNone} : evaluatePass(rendered[b], truth[b], display);
  };
  ViewMetrics m;
  m.diffuse = pass(Buffer::Diffuse);
  m.specular = pass(Buffer::Specular);
  m.final = pass(Buffer::Render);
  const Image& depth = truth[Buffer::Depth];
  m.depthRmse = depth.empty() ? kNone : depthRmse(rendered[Buffer::Depth], depth);
  // Without true depth every pixel counts as a surface for the normal error.
  const Image everySurface =
      depth.empty() ? Image(rendered[Buffer::Normal].width, rendered[Buffer::Normal].height, 1, 1.0f) : Image();
  m.normalAngleDegrees =
      truth[Buffer::Normal].empty()
          ? kNone
          : normalAngleDegrees(rendered[Buffer::Normal], truth[Buffer::Normal], depth.empty() ? everySurface : depth);
  return m;
}

ViewMetrics averageViewMetrics(std::span<const ViewMetrics> views) {
  ViewMetrics m;
  m.diffuse = averagePass(views, &ViewMetrics::diffuse);
  m.specular = averagePass(views, &ViewMetrics::specular);
  m.final = averagePass(views, &ViewMetrics::final);
  m.depthRmse = meanOfFinite(views, [](const ViewMetrics& v) { return v.depthRmse; });
  m.normalAngleDegrees = meanOfFinite(views, [](const ViewMetrics& v) { return v.normalAngleDegrees; });
  return m;
}

nlohmann::json toJson(const ViewMetrics& metrics) {
  return {{"diffuse", passJson(metrics.diffuse)},
          {"specular", passJson(metrics.specular)},
          {"final", passJson(metrics.final)},
          {"depth_rmse", number(metrics.depthRmse)},
          {"normal_angle_deg", number(metrics.normalAngleDegrees)}};
}

std::string formatMetric(double x, int decimals) {
  if (std::isnan(x)) return "-";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

ViewMetrics viewMetricsFromJson(const nlohmann::json& j, const std::string& file, const std::string& where) {
  if (!j.is_object()) throw Error(file, "key \"" + where + "\" is not an object");
  ViewMetrics m;
  m.diffuse = passFromJson(j, "diffuse", file, where);
  m.specular = passFromJson(j, "specular", file, where);
  m.final = passFromJson(j, "final", file, where);
  m.depthRmse = numberAt(j, "depth_rmse", file, where);
  m.normalAngleDegrees = numberAt(j, "normal_angle_deg", file, where);
  return m;
}

}  // namespace glint
