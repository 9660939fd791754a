// Gaussian scene PLY layouts: telling them apart, and mapping named PLY columns to
// GaussianScene arrays and back through the parameter table's property names
// (scene/gaussian_parameters.h).
#include "scene/gaussian_ply.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/gaussian_parameters.h"
#include "scene/imported_materials.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

constexpr const char* kGlintComment = "Glint Gaussian scene";

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

bool startsWith(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

bool hasCommentStartingWith(const PlyTable& table, const char* prefix) {
  return std::any_of(table.comments.begin(), table.comments.end(),
                     [&](const std::string& c) { return startsWith(c, prefix); });
}

// The first property only 3DGS writes (f_rest_*, nx, ny, nz), or empty.
std::string first3dgsOnlyProperty(const PlyTable& table) {
  for (const std::string& name : table.names) {
    if (startsWith(name, "f_rest_") || name == "nx" || name == "ny" || name == "nz") return name;
  }
  return "";
}

// The first of Glint's material properties (normal, roughness, F0), or empty.
std::string firstGlintMaterialProperty(const PlyTable& table) {
  std::string found;
  forEachParameterInPlyOrder([&](const auto& p) {
    if (p.plyRequired) return;
    for (const char* name : p.plyNames)
      if (found.empty() && table.has(name)) found = name;
  });
  return found;
}

// The number of f_rest_* properties.
int countShRest(const PlyTable& table) {
  return int(std::count_if(table.names.begin(), table.names.end(),
                           [](const std::string& name) { return startsWith(name, "f_rest_"); }));
}

// The lowest SH degree whose coefficients hold count f_rest properties (at most 3).
int shDegreeOf(int count) {
  int degree = 0;
  while (degree < kMaxShDegree && 3 * shRestPerChannel(degree) < count) ++degree;
  return degree;
}

// A number as %g writes it: "0.9", "2.5", "1".
std::string shortNumber(float value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", double(value));
  return text;
}

// Gaussians with a non-zero f_rest_* value.
size_t countNonZeroShRest(const PlyTable& table) {
  std::vector<bool> nonZero(table.count, false);
  for (size_t c = 0; c < table.names.size(); ++c) {
    if (!startsWith(table.names[c], "f_rest_")) continue;
    for (size_t i = 0; i < table.count; ++i) nonZero[i] = nonZero[i] || table.columns[c][i] != 0.0f;
  }
  return size_t(std::count(nonZero.begin(), nonZero.end(), true));
}

// Gives a 3DGS scene the materials its file lacks and decodes its colour.
void importThreeDgs(const PlyTable& table, bool hasNormals, bool hasRoughness, bool hasF0, GaussianScene& scene,
                    GaussianPlyImport& info) {
  info.colour = splatColourFromComments(table.comments, sourceName(table)).value_or(SplatColourEncoding{});
  for (Rgb& c : scene.diffuse)
    for (int k = 0; k < 3; ++k) c[k] = decodeSplatColour(c[k], info.colour);
  if (!hasNormals) setShortestAxisNormals(scene, medianPosition(scene));
  if (!hasRoughness) std::fill(scene.roughness.begin(), scene.roughness.end(), kImportedRoughness);
  if (!hasF0) std::fill(scene.f0.begin(), scene.f0.end(), Rgb(kImportedF0));
  info.normalsSet = !hasNormals;
  info.roughnessSet = !hasRoughness;
  info.f0Set = !hasF0;
  info.shDegree = shDegreeOf(countShRest(table));
  info.gaussiansWithShRest = countNonZeroShRest(table);
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

int shRestPerChannel(int degree) { return (degree + 1) * (degree + 1) - 1; }

PlyLayout detectGaussianPlyLayout(const PlyTable& table, bool* assumedThreeDgs) {
  auto ambiguous = [&](const std::string& why) {
    return Error(sourceName(table), "cannot tell whether f_dc_0..2 is Glint's linear colour or 3DGS's SH "
                                    "coefficient: " + why + "; pass --input-layout glint or --input-layout 3dgs");
  };
  if (assumedThreeDgs) *assumedThreeDgs = false;
  // What Glint wrote says so in a comment; only then can the file contradict itself.
  const bool glintComment = hasCommentStartingWith(table, kGlintComment);
  const bool exportComment = std::any_of(table.comments.begin(), table.comments.end(), isSplatColourComment);
  const std::string glintOnly = firstGlintMaterialProperty(table);
  const std::string splatOnly = first3dgsOnlyProperty(table);
  if (glintComment) {
    if (exportComment) throw ambiguous("the header carries both Glint's scene and 3DGS export comments");
    if (!splatOnly.empty()) throw ambiguous("its header says Glint's layout, but it has 3DGS's '" + splatOnly + "'");
    return PlyLayout::Glint;
  }
  if (exportComment) return PlyLayout::ThreeDgs;
  // Glint's material properties without any of 3DGS's own: Glint's layout, header lost.
  if (!glintOnly.empty() && splatOnly.empty()) return PlyLayout::Glint;
  // Everything else is what splat tools write (a degree-0 file has only the shared
  // properties); the caller says so when nothing but the missing header decided.
  if (assumedThreeDgs) *assumedThreeDgs = splatOnly.empty();
  return PlyLayout::ThreeDgs;
}

std::string describeImport(const GaussianPlyImport& import) {
  if (import.layout != PlyLayout::ThreeDgs) return "";
  std::string line = import.layoutAssumed
                         ? "no Glint header or material properties, so read as a 3DGS file (--input-layout glint "
                           "reads it as Glint's); colour read as "
                         : "imported 3DGS layout: colour read as ";
  if (import.colour.colour == SplatColourSpace::Linear) {
    line += "linear";
  } else {
    line += "display-referred (inverse filmic tonemap, exposure " + shortNumber(import.colour.exposure) + ")";
  }
  if (!import.normalsSet && !import.roughnessSet && !import.f0Set) return line + "; materials from the file";
  std::vector<std::string> set;
  if (import.roughnessSet) set.push_back("roughness " + shortNumber(kImportedRoughness));
  if (import.f0Set) set.push_back("F0 " + shortNumber(kImportedF0));
  if (import.normalsSet)
    set.push_back("normals along each Gaussian's shortest axis, facing away from the median position");
  line += "; materials set to a rough dielectric (";
  for (size_t i = 0; i < set.size(); ++i) line += (i > 0 ? ", " : "") + set[i];
  return line + ")";
}

std::string droppedShWarning(const GaussianPlyImport& import, const std::string& file) {
  if (import.gaussiansWithShRest == 0) return "";
  return "warning: " + file + ": " + std::to_string(import.gaussiansWithShRest) +
         " Gaussians have non-zero f_rest coefficients (SH degree " + std::to_string(import.shDegree) +
         "); Glint keeps only the DC colour, so their view-dependent colour is dropped";
}

GaussianScene gaussianSceneFromPly(const PlyTable& table, PlyLayout layout, GaussianPlyImport* import) {
  // Look every column up first, in the file's order, so that a missing property is
  // reported before any work (and before the layout is judged).
  std::array<std::vector<const std::vector<float>*>, kGaussianParameterCount> columns;
  forEachParameterInPlyOrder(
      [&](const auto& p) { columns[p.index] = columnGroup(table, p.plyNames, p.plyRequired); });
  bool layoutAssumed = false;
  if (layout == PlyLayout::Auto) layout = detectGaussianPlyLayout(table, &layoutAssumed);

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
  GaussianPlyImport info;
  info.layout = layout;
  info.layoutAssumed = layoutAssumed;
  if (layout == PlyLayout::ThreeDgs) {
    auto present = [&](auto member) { return !columns[parameterOf(member).index].empty(); };
    importThreeDgs(table, present(&GaussianScene::normal), present(&GaussianScene::roughness),
                   present(&GaussianScene::f0), scene, info);
  }
  if (import) *import = info;
  return scene;
}

GaussianScene readGaussianPly(const fs::path& path, PlyLayout layout, GaussianPlyImport* import) {
  return gaussianSceneFromPly(readPly(path, "vertex"), layout, import);
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
  writePly(path, table, {{std::string(kGlintComment) + ": f_dc_0..2 is linear diffuse colour (not SH)"}});
}

void exportGaussianPly3dgs(const fs::path& path, const GaussianScene& scene, const ThreeDgsExportOptions& options) {
  GLINT_CHECK(scene.consistent(), "exportGaussianPly3dgs: the scene's arrays have different sizes");
  GLINT_CHECK(options.shDegree >= 0 && options.shDegree <= kMaxShDegree, "exportGaussianPly3dgs: SH degree out of range");
  GLINT_CHECK(options.colour.exposure > 0.0f && std::isfinite(options.colour.exposure),
              "exportGaussianPly3dgs: exposure must be positive");
  const size_t n = scene.size();
  const size_t restCount = size_t(3 * shRestPerChannel(options.shDegree));
  GLINT_CHECK(!options.baked || (options.baked->consistent(n) && options.baked->shDegree == options.shDegree &&
                                  options.colour.colour == SplatColourSpace::Display),
              "exportGaussianPly3dgs: baked colours of another scene, degree or colour encoding");
  PlyTable table;
  table.count = n;
  addParameter(table, scene, parameterOf(&GaussianScene::position));
  for (const char* name : {"nx", "ny", "nz"}) table.add(name, std::vector<float>(n, 0.0f));
  for (int k = 0; k < 3; ++k) {
    std::vector<float> column(n);
    for (size_t i = 0; i < n; ++i)
      column[i] = options.baked ? float((double(options.baked->base[i][k]) - 0.5) / kShC0)
                                : encodeSplatColour(scene.diffuse[i][k], options.colour);
    table.add("f_dc_" + std::to_string(k), std::move(column));
  }
  // Channel-major: the coefficients of red, then green, then blue.
  const size_t perChannel = restCount / 3;
  for (size_t k = 0; k < restCount; ++k) {
    std::vector<float> column(n, 0.0f);
    if (options.baked)
      for (size_t i = 0; i < n; ++i) column[i] = options.baked->rest(i)[k % perChannel][int(k / perChannel)];
    table.add("f_rest_" + std::to_string(k), std::move(column));
  }
  // Opacity, scale and rotation are stored as in Glint's layout.
  addParameter(table, scene, parameterOf(&GaussianScene::opacityLogit));
  addParameter(table, scene, parameterOf(&GaussianScene::logScale));
  addParameter(table, scene, parameterOf(&GaussianScene::rotation));
  // The comment says how f_dc encodes the colour, so that Glint reads its own export back exactly.
  writePly(path, table, {{splatColourComment(options.colour)}});
}

}  // namespace glint
