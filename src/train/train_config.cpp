// TrainConfig <-> JSON. One list of fields (forEachField) drives writing, reading and the
// unknown-key check, so a new hyper-parameter is added in one place.
#include "train/train_config.h"

#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/json_file.h"
#include "scene/gaussian_parameters.h"
#include "train/depth_consistency.h"

namespace glint {

// {"min": [x, y, z], "max": [x, y, z], "count": n}; nlohmann's exceptions name what is wrong.
void to_json(nlohmann::json& j, const FarFieldBox& b) {
  j = {{"min", {jsonNumber(b.min.x), jsonNumber(b.min.y), jsonNumber(b.min.z)}},
       {"max", {jsonNumber(b.max.x), jsonNumber(b.max.y), jsonNumber(b.max.z)}},
       {"count", b.count}};
}

void from_json(const nlohmann::json& j, FarFieldBox& b) {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "min" && it.key() != "max" && it.key() != "count")
      throw std::invalid_argument("unknown key \"" + it.key() + "\" (a box has min, max and count)");
  auto corner = [&](const char* key) {
    const nlohmann::json& c = j.at(key);
    if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() || !c[2].is_number())
      throw std::invalid_argument(std::string("\"") + key + "\" must be an array of 3 numbers");
    for (const nlohmann::json& v : c)
      if (!(std::abs(v.get<double>()) <= double(std::numeric_limits<float>::max())))
        throw std::invalid_argument(std::string("\"") + key + "\" must hold finite numbers");
    auto v = c.get<std::array<float, 3>>();
    return Vec3f(v[0], v[1], v[2]);
  };
  b.min = corner("min");
  b.max = corner("max");
  const nlohmann::json& count = j.at("count");
  if (!count.is_number_integer() || (count.is_number_unsigned() ? count.get<uint64_t>() > uint64_t(kMaxFarFieldCount)
                                                                  : count.get<int64_t>() > kMaxFarFieldCount))
    throw std::invalid_argument("\"count\" must be an integer of at most " + std::to_string(kMaxFarFieldCount));
  b.count = count.get<int>();
}

namespace {

template <typename T>
constexpr bool kIsVector = false;
template <typename T>
constexpr bool kIsVector<std::vector<T>> = true;

// Calls f(section, key, field) for every field; section "" is the top level.
template <typename Config, typename F>
void forEachField(Config& c, F&& f) {
  f("", "dataset", c.dataset);
  f("", "holdout", c.holdout);
  f("", "background", c.background);
  f("", "downscale", c.downscale);
  f("", "iters", c.iters);
  f("", "seed", c.seed);
  f("", "threads", c.threads);
  f("", "bounces", c.bounces);
  f("", "render_bounces", c.renderBounces);
  f("", "baseline", c.baseline);
  f("", "reflection_warmup", c.reflectionWarmup);
  f("", "f0_tint_from_reflections", c.f0TintFromReflections);
  f("", "roughness_shift_invariant", c.roughnessShiftInvariant);
  f("", "invalid_normal_length", c.invalidNormalLength);
  f("", "backface_skip", c.backfaceSkip);
  f("", "batch_rays", c.batchRays);
  f("", "batch_views", c.batchViews);
  f("", "batch_images", c.batchImages);
  f("", "eval_every", c.evalEvery);
  f("", "save_every", c.saveEvery);
  f("", "scale_decay", c.scaleDecay);
  f("loss", "diffuse", c.loss.diffuse);
  f("loss", "depth", c.loss.depth);
  f("loss", "normal", c.loss.normal);
  f("loss", "roughness", c.loss.roughness);
  f("loss", "f0", c.loss.f0);
  f("loss", "specular", c.loss.specular);
  f("loss", "depth_band", c.loss.depthBand);
  f("loss", "depth_consistency", c.loss.depthConsistency);
  f("loss", "depth_consistency_views", c.loss.depthConsistencyViews);
  f("loss", "normal_huber", c.loss.normalHuber);
  f("loss", "roughness_from_specular", c.loss.roughnessFromSpecular);
  f("loss", "f0_from_specular", c.loss.f0FromSpecular);
  f("loss", "f0_tint_prior", c.loss.f0TintPrior);
  f("loss", "photograph", c.loss.photograph);
  // The learning rates, named by the parameter table.
  forEachParameter([&](const auto& p) {
    f("lr", p.rate.key, c.lr.*p.rate.initial);
    if (!p.rate.final) return;
    f("lr", p.rate.finalKey, c.lr.*p.rate.final);
    f("lr", p.rate.decayStepsKey, c.lr.*p.rate.decaySteps);
    f("lr", p.rate.decayStartKey, c.lr.*p.rate.decayStart);
  });
  f("adam", "beta1", c.adam.beta1);
  f("adam", "beta2", c.adam.beta2);
  f("adam", "epsilon", c.adam.epsilon);
  f("prune", "every", c.prune.every);
  f("prune", "start", c.prune.start);
  f("prune", "weight_threshold", c.prune.weightThreshold);
  f("prune", "threshold_pixels", c.prune.thresholdPixels);
  f("prune", "camera_sphere_factor", c.prune.cameraSphereFactor);
  f("prune", "camera_cull_region", c.prune.cameraCullRegion);
  f("densify", "fraction", c.densify.fraction);
  f("densify", "every", c.densify.every);
  f("densify", "start", c.densify.start);
  f("densify", "stop", c.densify.stop);
  f("densify", "max_gaussians", c.densify.maxGaussians);
  f("init", "source", c.initSource);
  f("init", "pixel_stride", c.init.pixelStride);
  f("init", "max_pixel_samples", c.init.maxPixelSamples);
  f("init", "voxel_fraction", c.init.voxelFraction);
  f("init", "min_samples_per_voxel", c.init.minSamplesPerVoxel);
  f("init", "depth_residual_voxels", c.init.depthResidualVoxels);
  f("init", "consistent_depth_only", c.initConsistentDepthOnly);
  f("init", "neighbours", c.init.neighbours);
  f("init", "opacity", c.init.opacity);
  f("init", "roughness", c.init.roughness);
  f("init", "f0", c.init.f0);
  f("cameras", "refine_every", c.cameras.every);
  f("cameras", "refine_until", c.cameras.until);
  f("far_field", "count", c.farField.count);
  f("far_field", "sigma_factor", c.farField.sigmaFactor);
  f("far_field", "truncation", c.farField.truncation);
  f("far_field", "opacity", c.farField.opacity);
  f("far_field", "diffuse", c.farField.diffuse);
  f("far_field", "neighbours", c.farField.neighbours);
  f("far_field", "boxes", c.farField.boxes);
  f("far_field", "reflection_seeds", c.farField.reflectionSeeds);
  f("far_field", "reflection_seed_roughness", c.farField.reflectionSeedRoughness);
  f("trace", "kernel_power", c.trace.kernelPower);
  f("trace", "alpha_min", c.trace.alphaMin);
  f("trace", "min_transmittance", c.trace.minTransmittance);
  f("trace", "exact_tail", c.trace.exactTail);
}

// Whether a JSON integer fits the field's type (nlohmann's get<> would wrap it:
// 4294967297 becomes 1 in an int).
template <typename Field>
bool integerFits(const nlohmann::json& v) {
  if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<Field>::max());
  const int64_t x = v.get<int64_t>();
  if constexpr (std::is_signed_v<Field>)
    return x >= int64_t(std::numeric_limits<Field>::min()) && x <= int64_t(std::numeric_limits<Field>::max());
  else
    return x >= 0;
}

// Whether a JSON number is finite in the field's type (1e39 is a finite double but an
// infinite float).
template <typename Field>
bool numberFits(const nlohmann::json& v) {
  return std::abs(v.get<double>()) <= double(std::numeric_limits<Field>::max());
}

// The JSON form of one field: a choice enum is written as its word, a float as its
// shortest decimal.
template <typename Field>
nlohmann::json jsonValue(const Field& field) {
  if constexpr (Choice<Field>)
    return choiceName(field);
  else if constexpr (std::is_same_v<Field, float>)
    return jsonNumber(field);
  else
    return field;
}

std::string keyName(const char* section, const char* key) {
  return std::string(section).empty() ? std::string(key) : std::string(section) + "." + key;
}

void require(bool ok, const std::string& source, const std::string& problem) {
  if (!ok) throw Error(source, problem);
}

}  // namespace

nlohmann::json toJson(const TrainConfig& config) {
  nlohmann::json j = nlohmann::json::object();
  forEachField(config, [&](const char* section, const char* key, const auto& field) {
    if (std::string(section).empty())
      j[key] = jsonValue(field);
    else
      j[section][key] = jsonValue(field);
  });
  return j;
}

void applyJson(const nlohmann::json& json, TrainConfig* config, const std::string& source) {
  require(json.is_object(), source, "is not a JSON object of training settings");
  // Which decaying rates are constant (final equal to initial) before these settings.
  std::array<bool, kGaussianParameterCount> constantRate{};
  forEachParameter([&](const auto& p) {
    constantRate[p.index] = p.rate.final && config->lr.*p.rate.initial == config->lr.*p.rate.final;
  });
  std::set<std::string> known;
  forEachField(*config, [&](const char* section, const char* key, auto& field) {
    known.insert(keyName(section, key));
    const nlohmann::json* node = &json;
    if (!std::string(section).empty()) {
      auto s = json.find(section);
      if (s == json.end()) return;
      require(s->is_object(), source, std::string("\"") + section + "\" must be an object");
      node = &*s;
    }
    auto v = node->find(key);
    if (v == node->end()) return;
    using Field = std::decay_t<decltype(field)>;
    bool typeOk = kIsVector<Field>                    ? v->is_array()
                  : std::is_same_v<Field, std::string> || Choice<Field> ? v->is_string()
                  : std::is_same_v<Field, bool>      ? v->is_boolean()
                  : std::is_integral_v<Field>        ? v->is_number_integer()
                                                     : v->is_number();
    if (!typeOk) {
      // Built by appending: GCC 12 warns falsely (-Wrestrict) on the chained operator+.
      std::string problem = "\"";
      problem.append(keyName(section, key)).append("\" has the wrong type (").append(v->type_name()).append(")");
      throw Error(source, problem);
    }
    bool fits = true;
    if constexpr (std::is_integral_v<Field> && !std::is_same_v<Field, bool>) fits = integerFits<Field>(*v);
    if constexpr (std::is_floating_point_v<Field>) fits = numberFits<Field>(*v);
    if (!fits) {
      std::string problem = "\"";
      problem.append(keyName(section, key)).append("\" is ").append(printableText(v->dump())).append(", out of the range of its type");
      throw Error(source, problem);
    }
    if constexpr (Choice<Field>) {
      std::optional<Field> choice = choiceFromName<Field>(v->get<std::string>());
      if (!choice) {
        std::string problem = "\"";
        problem.append(keyName(section, key)).append("\" is ").append(printableText(v->dump()));
        problem.append("; expected ").append(choiceList<Field>());
        throw Error(source, problem);
      }
      field = *choice;
      return;
    }
    try {
      field = v->get<Field>();
    } catch (const std::exception& e) {  // malformed elements of an array setting
      throw Error(source, "\"" + keyName(section, key) + "\": " + e.what());
    }
  });
  // A constant rate given only its initial value stays constant: {"lr": {"roughness": 1e-3}}
  // means 1e-3 throughout, not a schedule towards the old final value.
  if (auto lr = json.find("lr"); lr != json.end())
    forEachParameter([&](const auto& p) {
      if (constantRate[p.index] && lr->contains(p.rate.key) && !lr->contains(p.rate.finalKey))
        config->lr.*p.rate.final = config->lr.*p.rate.initial;
    });
  for (auto it = json.begin(); it != json.end(); ++it) {
    if (it->is_object()) {
      for (auto inner = it->begin(); inner != it->end(); ++inner)
        require(known.count(it.key() + "." + inner.key()) > 0, source,
                "has an unknown setting \"" + printableText(it.key() + "." + inner.key()) + "\"");
    } else {
      require(known.count(it.key()) > 0, source, "has an unknown setting \"" + printableText(it.key()) + "\"");
    }
  }
  config->validate(source);
}

void TrainConfig::validate(const std::string& source) const {
  // Every number first: a NaN passes any comparison written as "refuse if v < lo".
  forEachField(*this, [&](const char* section, const char* key, const auto& field) {
    using Field = std::decay_t<decltype(field)>;
    if constexpr (std::is_floating_point_v<Field>)
      require(std::isfinite(field), source, keyName(section, key) + " must be a finite number");
  });
  auto positive = [&](double v, const char* name) { require(v > 0, source, std::string(name) + " must be positive"); };
  auto inRange = [&](int64_t v, IntRange range, const char* name) {
    require(v >= range.min && v <= range.max, source,
            std::string(name) + " must be in [" + std::to_string(range.min) + ", " + std::to_string(range.max) + "]");
  };
  inRange(iters, kItersRange, "iters");
  inRange(holdout, kHoldoutRange, "holdout");
  inRange(downscale, kDownscaleRange, "downscale");
  inRange(batchRays, kBatchRaysRange, "batch_rays");
  inRange(batchViews, kBatchViewsRange, "batch_views");
  inRange(batchImages, kBatchImagesRange, "batch_images");
  inRange(evalEvery, kEveryStepsRange, "eval_every");
  inRange(saveEvery, kEveryStepsRange, "save_every");
  inRange(threads, kThreadsRange, "threads");
  inRange(bounces, kBouncesRange, "bounces");
  inRange(renderBounces, kRenderBouncesRange, "render_bounces");
  if (baseline == Baseline::Rgb)
    require(bounces == 0 && loss.depth == 0 && loss.normal == 0 && loss.roughness == 0 && loss.f0 == 0 &&
                loss.specular == 0,
            source, "baseline \"rgb\" trains on the render buffer alone: bounces and the G-buffer and specular "
                    "loss weights must be 0");
  checkFarFieldSettings(farField, source);
  checkDensifySettings(densify, source);
  require(reflectionWarmup >= 0, source, "reflection_warmup must be non-negative");
  require(loss.depthBand >= 0, source, "loss.depth_band must be non-negative (0 = off)");
  require(loss.normalHuber >= 0 && loss.normalHuber <= 2, source,
          "loss.normal_huber must be in [0, 2] (the Huber width of a normal component; 0 = L1)");
  require(loss.depthConsistency >= 0 && loss.depthConsistency < 1, source,
          "loss.depth_consistency must be in [0, 1) (a fraction of the depth; 0 = off)");
  require(loss.depthConsistencyViews >= 1 && loss.depthConsistencyViews <= kDepthConsistencyNeighbours, source,
          "loss.depth_consistency_views must be in [1, 8] (of the 8 neighbouring views each view is checked against)");
  require(!initConsistentDepthOnly || loss.depthConsistency > 0, source,
          "init.consistent_depth_only needs loss.depth_consistency > 0: the check's tolerance decides which depth "
          "pixels are trusted");
  require(!initConsistentDepthOnly || initSource != InitChoice::PointCloud, source,
          "init.consistent_depth_only applies to the depth buffers; init.source \"point-cloud\" does not read them");
  require(cameras.every >= 0 && cameras.every <= kEveryStepsRange.max, source,
          "cameras.refine_every must be in [0, " + std::to_string(kEveryStepsRange.max) + "] (0 = off)");
  require(cameras.until >= 0 && cameras.until <= kItersRange.max, source,
          "cameras.refine_until must be in [0, " + std::to_string(kItersRange.max) + "] (0 = three quarters of iters)");
  for (float w : {loss.roughnessFromSpecular, loss.f0FromSpecular})
    require(w >= 0 && w <= kMaxLossWeight, source,
            "loss.roughness_from_specular and loss.f0_from_specular must be in [0, 1e6] (0 = off)");
  require(!f0TintFromReflections || loss.f0FromSpecular > 0, source,
          "f0_tint_from_reflections leaves F0's tint to L_r, which reaches F0 only with loss.f0_from_specular > 0");
  require(loss.f0TintPrior >= 0 && loss.f0TintPrior <= 1, source, "loss.f0_tint_prior must be in [0, 1]");
  require(invalidNormalLength >= 0 && invalidNormalLength <= 1, source, "invalid_normal_length must be in [0, 1]");
  require(backfaceSkip >= 0, source, "backface_skip must be non-negative");
  require(scaleDecay > 0 && scaleDecay <= 1, source, "scale_decay must be in (0, 1]");
  require(reflectionWarmup <= kItersRange.max, source,
          "reflection_warmup must be at most " + std::to_string(kItersRange.max));
  for (float w : {loss.diffuse, loss.depth, loss.normal, loss.roughness, loss.f0, loss.specular, loss.photograph})
    require(w >= 0 && w <= kMaxLossWeight, source, "loss weights must be in [0, 1e6]");
  forEachParameter([&](const auto& p) {
    for (float LearningRates::*rate : {p.rate.initial, p.rate.final})
      if (rate) require(lr.*rate >= 0 && lr.*rate < kMaxLearningRate, source, "learning rates must be in [0, 10)");
  });
  forEachParameter([&](const auto& p) {
    const ParameterRate& r = p.rate;
    if (!r.final) return;
    inRange(lr.*r.decaySteps, kEveryStepsRange, keyName("lr", r.decayStepsKey).c_str());
    inRange(lr.*r.decayStart, kDecayStartRange, keyName("lr", r.decayStartKey).c_str());
    require(lr.*r.final <= lr.*r.initial, source,
            keyName("lr", r.finalKey) + " must not exceed " + keyName("lr", r.key));
  });
  require(adam.beta1 >= 0 && adam.beta1 < 1 && adam.beta2 >= 0 && adam.beta2 < 1, source,
          "adam.beta1 and adam.beta2 must be in [0, 1)");
  require(adam.epsilon > 0 && adam.epsilon <= 1, source, "adam.epsilon must be in (0, 1]");
  inRange(prune.every, kEveryStepsRange, "prune.every");
  require(prune.start >= 0, source, "prune.start must be non-negative");
  require(prune.weightThreshold >= 0, source, "prune.weight_threshold must be non-negative");
  require(prune.thresholdPixels >= 0 && prune.thresholdPixels <= 1e9, source,
          "prune.threshold_pixels must be in [0, 1e9] (0 = per training image)");
  require(prune.cameraSphereFactor >= 0 && prune.cameraSphereFactor < 1, source,
          "prune.camera_sphere_factor must be in [0, 1)");
  require(init.pixelStride >= 0 && init.pixelStride <= 16384, source,
          "init.pixel_stride must be in [0, 16384] (0 = automatic)");
  inRange(init.maxPixelSamples, {1, kMaxInitialSamples}, "init.max_pixel_samples");
  require(init.neighbours >= 1 && init.neighbours <= 64, source, "init.neighbours must be in [1, 64]");
  require(init.voxelFraction > 0 && init.voxelFraction <= 1, source, "init.voxel_fraction must be in (0, 1]");
  positive(init.minSamplesPerVoxel, "init.min_samples_per_voxel");
  require(init.opacity > 0 && init.opacity < 1, source, "init.opacity must be in (0, 1)");
  require(init.roughness >= 0 && init.roughness <= 1, source, "init.roughness must be in [0, 1]");
  require(init.f0 >= 0 && init.f0 <= 1, source, "init.f0 must be in [0, 1]");
  require(trace.kernelPower >= 0.25f && trace.kernelPower <= 16, source, "trace.kernel_power must be in [0.25, 16]");
  require(trace.alphaMin > 0 && trace.alphaMin < 0.5f, source, "trace.alpha_min must be in (0, 0.5)");
  require(trace.minTransmittance > 0 && trace.minTransmittance < 1, source,
          "trace.min_transmittance must be in (0, 1)");
}

void usePredictedBufferSetting(TrainConfig* config) {
  config->bounces = 2;
  config->loss.depth = 0.0f;
  config->loss.specular = 0.01f;
}

TrainConfig readTrainConfig(const std::filesystem::path& path) {
  TrainConfig config;
  applyJson(readJsonFile(path), &config, path.string());
  return config;
}

}  // namespace glint
