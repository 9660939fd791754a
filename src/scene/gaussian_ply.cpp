// Gaussian scene PLY layouts: mapping named PLY columns to GaussianScene arrays and back,
// through the parameter table's property names (scene/gaussian_parameters.h).
#include "scene/gaussian_ply.h"

#include <array>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/gaussian_parameters.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string sourceName(const PlyTable& table) { return table.source.empty() ? "(PLY table)" : table.source; }

// The named column, or an Error saying this is not a Gaussian scene.
const std::vector<float>& required(const PlyTable& table, const std::string& name) {
  int index = table.find(name);
  if (index < 0) {
    throw Error(sourceName(table), "not a Gaussian scene: element '" + table.element + "' has no property '" + name + "'");
  }
  return table.columns[size_t(index)];
}

// The columns of a parameter's group (e.g. normal_0..2), looked up by name: a required
// group must be complete; an optional one is all present, or none (empty result).
template <size_t N>
std::vector<const std::vector<float>*> columnGroup(const PlyTable& table, const std::array<const char*, N>& names,
                                                   bool isRequired) {
  std::vector<const std::vector<float>*> columns;
  for (const char* name : names) {
    if (isRequired) columns.push_back(&required(table, name));
    else if (table.has(name)) columns.push_back(&table.columns[size_t(table.find(name))]);
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
  // Glint's optional groups (normal, roughness, F0) are what only Glint writes.
  bool hasGlintOnly = false;
  forEachParameter([&](const auto& p) { hasGlintOnly = hasGlintOnly || (!p.plyRequired && table.has(p.plyNames[0])); });
  return has3dgsOnly && !hasGlintOnly ? PlyLayout::ThreeDgs : PlyLayout::Glint;
}

GaussianScene gaussianSceneFromPly(const PlyTable& table, PlyLayout layout) {
  if (layout == PlyLayout::Auto) layout = detectGaussianPlyLayout(table);

  // Look every column up first, in the file's order, so that a missing property is
  // reported before any work.
  std::array<std::vector<const std::vector<float>*>, kGaussianParameterCount> columns;
  forEachParameterInPlyOrder(
      [&](const auto& p) { columns[p.index] = columnGroup(table, p.plyNames, p.plyRequired); });

  GaussianScene scene;
  scene.resize(table.count);  // absent optional groups keep their neutral values
  forEachParameter([&](const auto& p) {
    const auto& group = columns[p.index];
    if (group.empty()) return;
    auto& values = scene.*p.values;
    for (size_t i = 0; i < table.count; ++i)
      for (int k = 0; k < p.components; ++k) component(values[i], k) = (*group[size_t(k)])[i];
  });
  for (size_t i = 0; i < table.count; ++i) {
    const Quatf& q = scene.rotation[i];
    if (q.w == 0.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f) {
      throw Error(sourceName(table), "vertex " + std::to_string(i) + " has a zero rotation quaternion (rot_0..3 are all 0)");
    }
  }
  if (layout == PlyLayout::ThreeDgs) {
    for (Rgb& c : scene.diffuse)
      for (int k = 0; k < 3; ++k) c[k] = float(0.5 + kShC0 * double(c[k]));
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

// Adds one column per component of a parameter, named as the table names them.
template <typename Parameter>
void addParameter(PlyTable& table, const GaussianScene& scene, const Parameter& p) {
  const auto& values = scene.*p.values;
  for (int k = 0; k < p.components; ++k) {
    std::vector<float> column(values.size());
    for (size_t i = 0; i < values.size(); ++i) column[i] = component(values[i], k);
    table.add(p.plyNames[size_t(k)], std::move(column));
  }
}

}  // namespace

void writeGaussianPly(const fs::path& path, const GaussianScene& scene) {
  GLINT_CHECK(scene.consistent(), "writeGaussianPly: the scene's arrays have different sizes");
  PlyTable table;
  table.count = scene.size();
  forEachParameterInPlyOrder([&](const auto& p) { addParameter(table, scene, p); });
  // The comment tells a reader of the header that f_dc is not spherical harmonics.
  writePly(path, table, {{"Glint Gaussian scene: f_dc_0..2 is linear diffuse colour (not SH)"}});
}

void exportGaussianPly3dgs(const fs::path& path, const GaussianScene& scene) {
  // Linear colour as the DC term and all 45 f_rest as zeros (degree 3, no view dependence).
  SplatColour colour;
  colour.base = scene.diffuse;
  colour.shDegree = kMaxShDegree;
  colour.sh.assign(scene.size() * colour.restCount(), Rgb(0.0f));
  exportGaussianPly3dgs(path, scene, colour);
}

void exportGaussianPly3dgs(const fs::path& path, const GaussianScene& scene, const SplatColour& colour) {
  GLINT_CHECK(scene.consistent() && colour.consistent(scene.size()),
              "exportGaussianPly3dgs: the scene's arrays have different sizes");
  size_t n = scene.size();
  PlyTable table;
  table.count = n;
  addParameter(table, scene, parameterOf(&GaussianScene::position));
  for (const char* name : {"nx", "ny", "nz"}) table.add(name, std::vector<float>(n, 0.0f));
  for (int k = 0; k < 3; ++k) {
    std::vector<float> column(n);
    for (size_t i = 0; i < n; ++i) column[i] = float((double(colour.base[i][k]) - 0.5) / kShC0);
    table.add("f_dc_" + std::to_string(k), std::move(column));
  }
  const size_t rest = colour.restCount();
  for (int channel = 0; channel < 3; ++channel) {
    for (size_t k = 0; k < rest; ++k) {
      std::vector<float> column(n);
      for (size_t i = 0; i < n; ++i) column[i] = colour.rest(i)[k][channel];
      table.add("f_rest_" + std::to_string(size_t(channel) * rest + k), std::move(column));
    }
  }
  // Opacity, scale and rotation are stored as in Glint's layout.
  addParameter(table, scene, parameterOf(&GaussianScene::opacityLogit));
  addParameter(table, scene, parameterOf(&GaussianScene::logScale));
  addParameter(table, scene, parameterOf(&GaussianScene::rotation));
  writePly(path, table);
}

}  // namespace glint
