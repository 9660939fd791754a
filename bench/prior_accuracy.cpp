// How far a capture's priors, as Glint decodes them (relative depth aligned to the sparse
// points, normals to world space, metalness to F0), are from the exact buffers of the same
// cameras: the input bound of a capture's training (issue 44). Scores each view of a split
// of PRIORS against TRUTH (a capture of the same views with exact priors, e.g. `glint synth
// --layout capture --degrade none`): 8-bit PSNR of diffuse, specular and their sum, depth
// RMSE and the share of pixels whose aligned depth is more than 5% off, the mean normal
// angle, roughness and F0 mean absolute errors. Prints a table and writes JSON (--json).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/parallel.h"
#include "eval/image_metrics.h"
#include "scene/dataset.h"

using namespace glint;

namespace {

struct PriorScores {
  double diffusePsnr = NAN, specularPsnr = NAN, sumPsnr = NAN;
  double depthRmse = NAN, depthOff5 = NAN, depthMissing = NAN;
  double normalDegrees = NAN, roughnessError = NAN, f0Error = NAN;
};

// Mean |a - b| over the pixels where the truth has a surface, all channels.
double meanAbsError(const Image& a, const Image& b, const Image& truthDepth) {
  double sum = 0;
  size_t count = 0;
  for (size_t p = 0; p < truthDepth.pixels.size(); ++p) {
    if (!hasSurface(truthDepth.pixels[p])) continue;
    for (int c = 0; c < a.channels; ++c)
      sum += std::abs(double(a.pixels[p * size_t(a.channels) + size_t(c)]) - b.pixels[p * size_t(b.channels) + size_t(c)]);
    count += size_t(a.channels);
  }
  return count ? sum / double(count) : NAN;
}

PriorScores scoreView(const Dataset& priors, const Dataset& truth, const DatasetSplit& priorSplit,
                      const DatasetSplit& truthSplit, size_t v) {
  PriorScores s;
  const Image trueDepth = truth.loadBuffer(truthSplit, v, Buffer::Depth);
  auto has = [&](Buffer b) { return priors.findBufferFile(priorSplit.views[v], b).has_value(); };
  auto load = [&](Buffer b) { return priors.loadBuffer(priorSplit, v, b); };
  if (has(Buffer::Diffuse) && has(Buffer::Specular)) {
    const Image diffuse = load(Buffer::Diffuse), specular = load(Buffer::Specular);
    const Image trueDiffuse = truth.loadBuffer(truthSplit, v, Buffer::Diffuse);
    const Image trueSpecular = truth.loadBuffer(truthSplit, v, Buffer::Specular);
    Image sum = diffuse, trueSum = trueDiffuse;
    for (size_t i = 0; i < sum.pixels.size(); ++i)
      sum.pixels[i] += specular.pixels[i], trueSum.pixels[i] += trueSpecular.pixels[i];
    s.diffusePsnr = psnrTonemapped8Bit(diffuse, trueDiffuse);
    s.specularPsnr = psnrTonemapped8Bit(specular, trueSpecular);
    s.sumPsnr = psnrTonemapped8Bit(sum, trueSum);
  }
  if (has(Buffer::Depth)) {
    const Image depth = load(Buffer::Depth);
    s.depthRmse = depthRmse(depth, trueDepth);
    size_t off = 0, missing = 0, surface = 0;
    for (size_t p = 0; p < trueDepth.pixels.size(); ++p) {
      if (!hasSurface(trueDepth.pixels[p])) continue;
      ++surface;
      if (!hasSurface(depth.pixels[p])) ++missing;
      else if (std::abs(depth.pixels[p] - trueDepth.pixels[p]) > 0.05 * trueDepth.pixels[p]) ++off;
    }
    s.depthOff5 = surface ? double(off) / double(surface) : NAN;
    s.depthMissing = surface ? double(missing) / double(surface) : NAN;
  }
  if (has(Buffer::Normal))
    s.normalDegrees = normalAngleDegrees(load(Buffer::Normal), truth.loadBuffer(truthSplit, v, Buffer::Normal), trueDepth);
  if (has(Buffer::Roughness))
    s.roughnessError = meanAbsError(load(Buffer::Roughness), truth.loadBuffer(truthSplit, v, Buffer::Roughness), trueDepth);
  if (has(Buffer::F0)) s.f0Error = meanAbsError(load(Buffer::F0), truth.loadBuffer(truthSplit, v, Buffer::F0), trueDepth);
  return s;
}

// The mean of the finite values of one score over the views (NaN when none is finite).
double meanOf(const std::vector<PriorScores>& views, double PriorScores::*field) {
  double sum = 0;
  int count = 0;
  for (const PriorScores& s : views)
    if (std::isfinite(s.*field)) sum += s.*field, ++count;
  return count ? sum / count : NAN;
}

nlohmann::json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scores a capture's decoded priors against the exact buffers of the same views"};
  std::string priorsPath, truthPath, jsonPath;
  int holdout = Dataset::kDefaultHoldout;
  app.add_option("priors", priorsPath, "Capture whose priors are scored")->required();
  app.add_option("truth", truthPath, "Capture of the same views with exact priors")->required();
  app.add_option("--holdout", holdout, "Every N-th view is a test view (as glint train --holdout)")
      ->check(CLI::Range(2, 1000));
  app.add_option("--json", jsonPath, "Write the scores here");
  CLI11_PARSE(app, argc, argv);
  try {
    const Dataset priors = Dataset::open(priorsPath, true, holdout), truth = Dataset::open(truthPath, true, holdout);
    nlohmann::json out;
    std::printf("%-6s %6s %8s %8s %8s %10s %9s %9s %9s %10s %8s\n", "split", "views", "diffuse", "specular", "sum",
                "depth RMSE", "depth >5%", "no depth", "normal", "roughness", "F0");
    for (const char* name : {"train", "test"}) {
      const DatasetSplit& p = std::string(name) == "train" ? priors.train() : priors.test();
      const DatasetSplit& t = std::string(name) == "train" ? truth.train() : truth.test();
      if (p.views.size() != t.views.size())
        throw Error(priorsPath, std::string("its ") + name + " split has " + std::to_string(p.views.size()) +
                                    " views, the truth's " + std::to_string(t.views.size()));
      std::vector<PriorScores> views(p.views.size());
      parallelFor(int64_t(views.size()), 1, [&](int64_t v) { views[size_t(v)] = scoreView(priors, truth, p, t, size_t(v)); });
      PriorScores mean;
      for (auto field : {&PriorScores::diffusePsnr, &PriorScores::specularPsnr, &PriorScores::sumPsnr,
                         &PriorScores::depthRmse, &PriorScores::depthOff5, &PriorScores::depthMissing,
                         &PriorScores::normalDegrees, &PriorScores::roughnessError, &PriorScores::f0Error})
        mean.*field = meanOf(views, field);
      std::printf("%-6s %6zu %8.2f %8.2f %8.2f %10.4f %8.1f%% %8.1f%% %8.2f° %10.4f %8.4f\n", name, views.size(),
                  mean.diffusePsnr, mean.specularPsnr, mean.sumPsnr, mean.depthRmse, 100 * mean.depthOff5,
                  100 * mean.depthMissing, mean.normalDegrees, mean.roughnessError, mean.f0Error);
      out[name] = {{"views", views.size()},
                   {"diffuse_psnr_8bit", numberOrNull(mean.diffusePsnr)},
                   {"specular_psnr_8bit", numberOrNull(mean.specularPsnr)},
                   {"sum_psnr_8bit", numberOrNull(mean.sumPsnr)},
                   {"depth_rmse", numberOrNull(mean.depthRmse)},
                   {"depth_off_5_percent", numberOrNull(mean.depthOff5)},
                   {"depth_missing", numberOrNull(mean.depthMissing)},
                   {"normal_angle_deg", numberOrNull(mean.normalDegrees)},
                   {"roughness_mae", numberOrNull(mean.roughnessError)},
                   {"f0_mae", numberOrNull(mean.f0Error)}};
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prior_accuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
