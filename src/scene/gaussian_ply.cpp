// Gaussian scene PLY layouts: mapping named PLY columns to GaussianScene arrays and back.
#include "scene/gaussian_ply.h"

#include <array>
#include <string>
#include <vector>

#include "core/error.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// 3DGS stores SH up to degree 3: 15 coefficients beyond the DC term per colour channel.
constexpr int kShRestCount = 45;

std::string sourceName(const PlyTable& table) { return table.source.empty() ? "(PLY table)" : table.source; }

// The named column, or an Error saying this is not a Gaussian scene.
const std::vector<float>& required(const PlyTable& table, const std::string& name) {
  int index = table.find(name);
  if (index < 0) {
    throw Error(sourceName(table), "not a Gaussian scene: element '" + table.element + "' has no property '" + name + "'");
  }
  return table.columns[size_t(index)];
}

// The columns of an optional group (e.g. normal_0..2): all present, or none (empty result).
template <size_t N>
std::vector<const std::vector<float>*> optionalGroup(const PlyTable& table, const std::array<const char*, N>& names) {
  std::vector<const std::vector<float>*> columns;
  for (const char* name : names) {
    if (table.has(name)) columns.push_back(&table.columns[size_t(table.find(name))]);
  }
  if (!columns.empty() && columns.size() != N) {
    const char* present = nullptr;
    const char* missing = nullptr;
    for (const char* name : names) {  // the first present and the first missing one
      const char*& slot = table.has(name) ? present : missing;
      if (!slot) slot = name;
    }
    throw Error(sourceName(table), "incomplete Gaussian scene: element '" + table.element + "' has property '" +
                                       present + "' but not '" + missing + "'");
  }
  return columns;
}

Vec3f gather3(const std::vector<const std::vector<float>*>& c, size_t i) { return {(*c[0])[i], (*c[1])[i], (*c[2])[i]}; }

}  // namespace

const char* plyLayoutName(PlyLayout layout) {
  switch (layout) {
    case PlyLayout::Auto: return "auto";
    case PlyLayout::Glint: return "glint";
    case PlyLayout::ThreeDgs: return "3dgs";
  }
  return "";
}

PlyLayout detectGaussianPlyLayout(const PlyTable& table) {
  bool has3dgsOnly = table.has("f_rest_0") || table.has("nx");
  bool hasGlintOnly = table.has("normal_0") || table.has("roughness") || table.has("f0_0");
  return has3dgsOnly && !hasGlintOnly ? PlyLayout::ThreeDgs : PlyLayout::Glint;
}

GaussianScene gaussianSceneFromPly(const PlyTable& table, PlyLayout layout) {
  if (layout == PlyLayout::Auto) layout = detectGaussianPlyLayout(table);
  std::string file = sourceName(table);

  // Look every column up first, so that a missing property is reported before any work.
  const auto& x = required(table, "x");
  const auto& y = required(table, "y");
  const auto& z = required(table, "z");
  std::array<const std::vector<float>*, 3> colour, scale;
  std::array<const std::vector<float>*, 4> rot;
  for (int k = 0; k < 3; ++k) colour[k] = &required(table, "f_dc_" + std::to_string(k));
  const auto& opacity = required(table, "opacity");
  for (int k = 0; k < 3; ++k) scale[k] = &required(table, "scale_" + std::to_string(k));
  for (int k = 0; k < 4; ++k) rot[k] = &required(table, "rot_" + std::to_string(k));
  auto normal = optionalGroup(table, std::array<const char*, 3>{"normal_0", "normal_1", "normal_2"});
  auto roughness = optionalGroup(table, std::array<const char*, 1>{"roughness"});
  auto f0 = optionalGroup(table, std::array<const char*, 3>{"f0_0", "f0_1", "f0_2"});

  GaussianScene scene;
  scene.resize(table.count);  // defaults for absent optional groups: normal 0, roughness 0, F0 0.04
  for (size_t i = 0; i < table.count; ++i) {
    scene.position[i] = {x[i], y[i], z[i]};
    Quatf q{(*rot[0])[i], (*rot[1])[i], (*rot[2])[i], (*rot[3])[i]};
    if (q.w == 0.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f) {
      throw Error(file, "vertex " + std::to_string(i) + " has a zero rotation quaternion (rot_0..3 are all 0)");
    }
    scene.rotation[i] = q;
    scene.logScale[i] = {(*scale[0])[i], (*scale[1])[i], (*scale[2])[i]};
    scene.opacityLogit[i] = opacity[i];
    Rgb c{(*colour[0])[i], (*colour[1])[i], (*colour[2])[i]};
    if (layout == PlyLayout::ThreeDgs) {
      for (int k = 0; k < 3; ++k) c[k] = float(0.5 + kShC0 * double(c[k]));
    }
    scene.diffuse[i] = c;
    if (!normal.empty()) scene.normal[i] = gather3(normal, i);
    if (!roughness.empty()) scene.roughness[i] = (*roughness[0])[i];
    if (!f0.empty()) scene.f0[i] = gather3(f0, i);
  }
  return scene;
}

GaussianScene readGaussianPly(const fs::path& path, PlyLayout layout, PlyLayout* detected) {
  PlyTable table = readPly(path, "vertex");
  if (layout == PlyLayout::Auto) layout = detectGaussianPlyLayout(table);
  if (detected) *detected = layout;
  return gaussianSceneFromPly(table, layout);
}

namespace {

// Adds name_0.. name_{N-1} columns from component k of each element of values.
template <typename V>
void addComponents(PlyTable& table, const std::string& prefix, const std::vector<V>& values, int components,
                   float (*get)(const V&, int)) {
  for (int k = 0; k < components; ++k) {
    std::vector<float> column(values.size());
    for (size_t i = 0; i < values.size(); ++i) column[i] = get(values[i], k);
    table.add(prefix + std::to_string(k), std::move(column));
  }
}

float vecComponent(const Vec3f& v, int k) { return v[k]; }
float quatComponent(const Quatf& q, int k) { return k == 0 ? q.w : k == 1 ? q.x : k == 2 ? q.y : q.z; }

// Position, opacity, scale and rotation are stored alike in both layouts.
void addPosition(PlyTable& table, const GaussianScene& scene) {
  const char* names[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    std::vector<float> column(scene.size());
    for (size_t i = 0; i < scene.size(); ++i) column[i] = scene.position[i][k];
    table.add(names[k], std::move(column));
  }
}

void addShape(PlyTable& table, const GaussianScene& scene) {
  table.add("opacity", scene.opacityLogit);
  addComponents(table, "scale_", scene.logScale, 3, vecComponent);
  addComponents(table, "rot_", scene.rotation, 4, quatComponent);
}

}  // namespace

void writeGaussianPly(const fs::path& path, const GaussianScene& scene) {
  GLINT_CHECK(scene.consistent(), "writeGaussianPly: the scene's arrays have different sizes");
  PlyTable table;
  table.count = scene.size();
  addPosition(table, scene);
  addComponents(table, "f_dc_", scene.diffuse, 3, vecComponent);
  addShape(table, scene);
  addComponents(table, "normal_", scene.normal, 3, vecComponent);
  table.add("roughness", scene.roughness);
  addComponents(table, "f0_", scene.f0, 3, vecComponent);
  // The comment tells a reader of the header that f_dc is not spherical harmonics.
  writePly(path, table, {{"Glint Gaussian scene: f_dc_0..2 is linear diffuse colour (not SH)"}});
}

void exportGaussianPly3dgs(const fs::path& path, const GaussianScene& scene) {
  GLINT_CHECK(scene.consistent(), "exportGaussianPly3dgs: the scene's arrays have different sizes");
  size_t n = scene.size();
  PlyTable table;
  table.count = n;
  addPosition(table, scene);
  for (const char* name : {"nx", "ny", "nz"}) table.add(name, std::vector<float>(n, 0.0f));
  for (int k = 0; k < 3; ++k) {
    std::vector<float> column(n);
    for (size_t i = 0; i < n; ++i) column[i] = float((double(scene.diffuse[i][k]) - 0.5) / kShC0);
    table.add("f_dc_" + std::to_string(k), std::move(column));
  }
  for (int k = 0; k < kShRestCount; ++k) table.add("f_rest_" + std::to_string(k), std::vector<float>(n, 0.0f));
  addShape(table, scene);
  writePly(path, table);
}

}  // namespace glint
