// Loading a Gaussian scene from a .ply file or a training run folder (scene.ply + config.json).
#include "app/scene_source.h"

#include <algorithm>
#include <cctype>
#include <string>

#include <nlohmann/json.hpp>

#include "io/json_file.h"
#include "core/activity.h"
#include "core/error.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

using Json = nlohmann::json;

bool hasPlyExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".ply";
}

// One optional number of the "trace" object, checked against the range of its flag.
void readTraceValue(const Json& trace, const char* key, double low, double high, const fs::path& file, float& out) {
  if (!trace.contains(key)) return;
  const Json& value = trace[key];
  if (!value.is_number())
    throw Error(file.string(), std::string("\"trace\".\"") + key + "\" must be a number, got " + value.dump());
  double x = value.get<double>();
  if (!(x >= low && x <= high))
    throw Error(file.string(), std::string("\"trace\".\"") + key + "\" = " + value.dump() + " is outside [" +
                                   std::to_string(low) + ", " + std::to_string(high) + "]");
  out = float(x);
}

// Reads the parts of a run's config.json that rendering needs; other keys belong to the
// trainer and are ignored here.
void readRunConfig(const fs::path& file, SceneSource& source) {
  Json config = readJsonFile(file);
  if (!config.is_object()) throw Error(file.string(), "must hold a JSON object");
  if (config.contains("dataset")) {
    if (!config["dataset"].is_string())
      throw Error(file.string(), "\"dataset\" must be a path string, got " + config["dataset"].dump());
    source.dataset = config["dataset"].get<std::string>();
  }
  if (config.contains("trace")) {
    const Json& trace = config["trace"];
    if (!trace.is_object()) throw Error(file.string(), "\"trace\" must be an object, got " + trace.dump());
    // The same ranges as the --kernel-power, --alpha-min and --min-transmittance flags.
    readTraceValue(trace, "kernel_power", 0.25, 16.0, file, source.trace.kernelPower);
    readTraceValue(trace, "alpha_min", 1e-6, 0.5, file, source.trace.alphaMin);
    readTraceValue(trace, "min_transmittance", 0.0, 1.0, file, source.trace.minTransmittance);
    // A scene trained with the truncation tail estimate (appendix A.2) renders with it.
    if (trace.contains("exact_tail")) {
      if (!trace["exact_tail"].is_boolean())
        throw Error(file.string(), "\"trace\".\"exact_tail\" must be true or false, got " + trace["exact_tail"].dump());
      source.trace.exactTail = trace["exact_tail"].get<bool>();
    }
  }
}

}  // namespace

SceneSource loadSceneSource(const fs::path& p) {
  ActivityScope activity("reading the scene " + p.string());
  SceneSource source;
  if (fs::is_directory(p)) {
    fs::path scene = p / "scene.ply";
    if (!fs::is_regular_file(scene)) throw Error(p.string(), "is not a training run: no scene.ply");
    source.scene = readGaussianPly(scene);
    fs::path config = p / "config.json";
    if (fs::exists(config)) readRunConfig(config, source);
    return source;
  }
  if (!fs::exists(p))
    throw Error(p.string(), "does not exist (expected a Gaussian scene .ply or a training run folder)");
  if (!hasPlyExtension(p)) throw Error(p.string(), "is neither a Gaussian scene .ply nor a training run folder");
  source.scene = readGaussianPly(p);
  return source;
}

}  // namespace glint
