// The metrics of one evaluated view (every pass and G-buffer against the ground truth),
// their average over views, and their JSON form for metrics.json.
#pragma once

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "io/transfer.h"
#include "scene/buffers.h"

namespace glint {

// PSNR and SSIM of one radiance pass, in linear space and on tonemapped 8-bit images.
struct PassMetrics {
  double psnr = 0;
  double ssim = 0;
  double psnrTonemapped = 0;
  double ssimTonemapped = 0;
};

struct ViewMetrics {
  PassMetrics diffuse;
  PassMetrics specular;
  PassMetrics final;            // the 'render' buffer
  double depthRmse = 0;         // NaN when the view has no surface pixel
  double normalAngleDegrees = 0;
};

// The 8-bit metrics use `display` (image_metrics.h: filmic for Glint's linear datasets, a
// display-referred dataset's own transfer otherwise).
PassMetrics evaluatePass(const Image& predicted, const Image& truth, Transfer display = Transfer::Filmic);
// Compares a rendered view with its ground truth (see image_metrics.h for each metric).
ViewMetrics evaluateView(const ViewBuffers& rendered, const ViewBuffers& truth, Transfer display = Transfer::Filmic);

// The mean of each metric over the views where it is finite: a view without surface
// pixels has no depth error rather than a zero one, and a view rendered exactly (infinite
// PSNR) is left out of the PSNR mean instead of making it infinite. A metric finite in no
// view is NaN (infinite if every view had infinite PSNR).
ViewMetrics averageViewMetrics(std::span<const ViewMetrics> views);

// {"diffuse": {"psnr", "ssim", "psnr_tonemapped", "ssim_tonemapped"}, "specular": {...},
//  "final": {...}, "depth_rmse", "normal_angle_deg"}. JSON has no NaN or infinity: those
// become null.
nlohmann::json toJson(const ViewMetrics& metrics);

// "31.42" (that many decimals), "inf" for an exact match, "-" for a metric without a value (NaN).
std::string formatMetric(double x, int decimals);

// The inverse of toJson, null becoming NaN. `where` names the object in errors (e.g.
// "per_view[3]"); throws Error naming file and the key that is missing or not a number.
ViewMetrics viewMetricsFromJson(const nlohmann::json& j, const std::string& file, const std::string& where);

}  // namespace glint
