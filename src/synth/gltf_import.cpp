// Imports glTF 2.0 scenes into MeshScene: tinygltf parses the file and decodes images; this
// file walks the node tree, bakes transforms and maps materials and lights to Glint's.
#include "synth/gltf_import.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable_text.h"
#include "math/mat4.h"

namespace glint {
namespace {

// Extensions whose data this importer reads (or deliberately ignores with a warning, like
// KHR_texture_transform). A file that *requires* any other extension is rejected, as the
// glTF 2.0 specification (section 3.12) demands of loaders that do not support it.
const std::set<std::string> kHandledExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular",
    "KHR_materials_ior", "KHR_texture_transform"};

// IEC 61966-2-1 sRGB decoding (the exact piecewise EOTF, not a 2.2 power).
float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : static_cast<float>(std::pow((c + 0.055) / 1.055, 2.4));
}

// tinygltf messages are newline-separated; one line reads better inside our error.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
  return text;
}

const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

double numberOr(const tinygltf::Value* object, const char* key, double fallback) {
  if (!object || !object->Has(key) || !object->Get(key).IsNumber()) return fallback;
  return object->Get(key).GetNumberAsDouble();
}

Rgb rgbOr(const std::vector<double>& values, Rgb fallback) {
  return values.size() >= 3 ? Rgb(float(values[0]), float(values[1]), float(values[2])) : fallback;
}

Rgb rgbOr(const tinygltf::Value* object, const char* key, Rgb fallback) {
  if (!object || !object->Has(key)) return fallback;
  const tinygltf::Value& array = object->Get(key);
  if (!array.IsArray() || array.ArrayLen() < 3) return fallback;
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = float(array.Get(i).GetNumberAsDouble());
  return c;
}

// A node's local transform: a column-major matrix, or translation * rotation * scale.
Mat4 localTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    Mat4 m;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row) m.m[row][col] = node.matrix[col * 4 + row];
    return m;
  }
  Mat4 t = Mat4::identity(), r = Mat4::identity(), s = Mat4::identity();
  const auto& tv = node.translation;
  const auto& rv = node.rotation;  // glTF quaternion order: x, y, z, w
  const auto& sv = node.scale;
  if (tv.size() == 3) t = Mat4::translation({tv[0], tv[1], tv[2]});
  if (rv.size() == 4) r = Mat4::rotation(rv[3], rv[0], rv[1], rv[2]);
  if (sv.size() == 3) s = Mat4::scale({sv[0], sv[1], sv[2]});
  return t * r * s;
}

double determinant3x3(const Mat4& a) {
  const auto& m = a.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

bool hasGlbMagic(const std::filesystem::path& path) {
  char magic[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(magic, 4);
  return in && std::memcmp(magic, "glTF", 4) == 0;
}

// tinygltf's reader of external files (buffers, images) sizes its buffer by seeking to the
// end, which for a directory (a URI such as "%%" or "." names the file's own folder) gives
// 2^63 - 1 and throws std::bad_alloc. This one reads regular files only, by their size.
bool readExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::error_code ec;
  uintmax_t size = std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : 0;
  if (ec || size == 0) {
    if (err) *err += "File not found or not a regular non-empty file: " + path + "\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(size);
  if (!in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    if (err) *err += "File could not be read: " + path + "\n";
    return false;
  }
  return true;
}

// The elements of one accessor, checked to lie inside its buffer view and buffer.
struct AccessorView {
  std::string name;                     // "accessor 3 (primitive 'mesh#0' NORMAL)", for errors
  const unsigned char* data = nullptr;  // first element; null: no buffer view, all zeros
  size_t stride = 0;
  size_t count = 0;
  int componentType = 0;
  bool normalized = false;

  // Component c of element i as a float (normalized integers mapped per glTF 3.11).
  float component(size_t i, int c) const {
    if (!data) return 0.0f;
    const unsigned char* p = data + i * stride + size_t(c) * tinygltf::GetComponentSizeInBytes(uint32_t(componentType));
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? load<uint8_t>(p) / 255.0f : load<uint8_t>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return normalized ? load<uint16_t>(p) / 65535.0f : load<uint16_t>(p);
      default: return 0.0f;  // view() admits no other component type for vertex data
    }
  }
  uint32_t index(size_t i) const {
    if (!data) return 0;
    const unsigned char* p = data + i * stride;
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<uint8_t>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
      default: return load<uint32_t>(p);
    }
  }
  // glTF buffers are little-endian and need not be aligned for the component type.
  template <typename T>
  static T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
  }
};

class GltfImporter {
 public:
  explicit GltfImporter(const std::filesystem::path& path) : path_(path), source_(path.string()) {}

  MeshScene run() {
    load();
    addNodes(rootNodes());
    if (skippedPrimitives_ > 0)
      warnOnce("skipped " + std::to_string(skippedPrimitives_) +
               " primitive(s) that are not triangle lists (points, lines, strips and fans are not supported)");
    scene_.validate(source_);
    return std::move(scene_);
  }

 private:
  // Problems quote the file's names, URIs and tinygltf's messages: escaped for the terminal.
  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(source_, printableText(problem, std::string::npos));
  }

  void warnOnce(const std::string& message) {
    if (warned_.insert(message).second)
      std::fprintf(stderr, "glint: warning: %s: %s\n", source_.c_str(),
                   printableText(message, std::string::npos).c_str());
  }

  void load() {
    checkInputFile(path_);  // a FIFO or device would block or never end
    tinygltf::TinyGLTF loader;
    loader.SetPreserveImageChannels(true);  // keep grey images one channel instead of RGBA
    loader.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readExternalFile,
                           &tinygltf::WriteWholeFile, nullptr});
    std::string err, warn;
    bool ok = hasGlbMagic(path_) ? loader.LoadBinaryFromFile(&model_, &err, &warn, source_)
                                 : loader.LoadASCIIFromFile(&model_, &err, &warn, source_);
    // Checked before `ok`: tinygltf parses extensionsRequired first, then fails later with
    // a less helpful message on, for example, Draco-compressed accessors.
    for (const std::string& name : model_.extensionsRequired)
      if (!kHandledExtensions.count(name)) fail("requires extension " + name + " which Glint does not support");
    if (!ok) fail("could not be read as glTF 2.0: " + oneLine(err.empty() ? warn : err));
    if (model_.asset.version.rfind("2.", 0) != 0)
      fail("is glTF version " + model_.asset.version + "; only glTF 2.x is supported");
    loaderWarnings_ = oneLine(warn);
    if (!loaderWarnings_.empty()) warnOnce("tinygltf: " + loaderWarnings_);
    std::string ignored;
    for (const std::string& name : model_.extensionsUsed)
      if (!kHandledExtensions.count(name)) ignored += (ignored.empty() ? "" : ", ") + name;
    if (!ignored.empty()) warnOnce("ignoring extensions Glint does not support: " + ignored);
  }

  // The default scene's roots, scene 0's without a default, or every parentless node.
  std::vector<int> rootNodes() const {
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (s >= int(model_.scenes.size())) fail("default scene " + std::to_string(s) + " does not exist");
      return model_.scenes[s].nodes;
    }
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int child : node.children)
        if (child >= 0 && child < int(isChild.size())) isChild[child] = true;
    std::vector<int> roots;
    for (int i = 0; i < int(model_.nodes.size()); ++i)
      if (!isChild[i]) roots.push_back(i);
    return roots;
  }

  // Walks the node trees depth first, children in file order. With an explicit stack, not
  // recursion: a file of a few megabytes can chain a million nodes. glTF node hierarchies
  // are disjoint trees (section 3.5.3), so a node reached twice (a cycle, or a child shared
  // by two parents, which can make the walk exponential) is an error.
  void addNodes(const std::vector<int>& roots) {
    struct Pending {
      int index;
      Mat4 parent;
    };
    std::vector<Pending> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.push_back({*root, Mat4::identity()});
    std::vector<bool> reached(model_.nodes.size(), false);
    while (!stack.empty()) {
      Pending next = stack.back();
      stack.pop_back();
      if (next.index < 0 || next.index >= int(model_.nodes.size()))
        fail("refers to node " + std::to_string(next.index) + " but the file has " +
             std::to_string(model_.nodes.size()));
      if (reached[next.index])
        fail("node " + std::to_string(next.index) +
             " is reached twice (through a cycle or two parents); glTF node hierarchies must be trees");
      reached[next.index] = true;
      const tinygltf::Node& node = model_.nodes[next.index];
      Mat4 world = next.parent * localTransform(node);
      if (node.skin >= 0) warnOnce("skins are ignored: skinned meshes are placed by their node transform in bind pose");
      if (node.mesh >= 0) addMesh(node.mesh, world);
      addLight(node, world);
      for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
        stack.push_back({*child, world});
    }
  }

  void addMesh(int index, const Mat4& world) {
    if (index >= int(model_.meshes.size()))
      fail("refers to mesh " + std::to_string(index) + " but the file has " + std::to_string(model_.meshes.size()));
    const tinygltf::Mesh& mesh = model_.meshes[index];
    // Normals transform by the inverse transpose; a mirroring transform flips the winding.
    Mat4 inverse = world.inverse();
    bool mirrored = determinant3x3(world) < 0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        ++skippedPrimitives_;
        continue;
      }
      if (!primitive.targets.empty()) warnOnce("morph targets are ignored: meshes keep their base shape");
      TriangleMesh out;
      out.name = (mesh.name.empty() ? "mesh " + std::to_string(index) : mesh.name) + "#" + std::to_string(p);
      readPrimitive(primitive, out);
      for (Vec3f& x : out.positions) x = Vec3f(world.transformPoint(Vec3d(x)));
      for (Vec3f& n : out.normals) {
        Vec3d t(inverse.m[0][0] * n.x + inverse.m[1][0] * n.y + inverse.m[2][0] * n.z,
                inverse.m[0][1] * n.x + inverse.m[1][1] * n.y + inverse.m[2][1] * n.z,
                inverse.m[0][2] * n.x + inverse.m[1][2] * n.y + inverse.m[2][2] * n.z);
        n = Vec3f(normalize(t));
      }
      if (mirrored)
        for (size_t t = 0; t + 2 < out.indices.size(); t += 3) std::swap(out.indices[t + 1], out.indices[t + 2]);
      out.material = material(primitive.material);
      scene_.meshes.push_back(std::move(out));
    }
  }

  // Reads positions, normals, TEXCOORD_0 and indices in the primitive's local space. Every
  // accessor is checked before anything is allocated for any of them.
  void readPrimitive(const tinygltf::Primitive& primitive, TriangleMesh& out) {
    auto attribute = [&](const char* name) {
      auto it = primitive.attributes.find(name);
      return it == primitive.attributes.end() ? -1 : it->second;
    };
    const std::string what = "primitive '" + out.name + "'";
    int positionAccessor = attribute("POSITION");
    if (positionAccessor < 0) fail(what + " has no POSITION attribute");
    AccessorView positions = view(positionAccessor, what + " POSITION", TINYGLTF_TYPE_VEC3, false);
    std::optional<AccessorView> normals, uvs, indices;
    if (int a = attribute("NORMAL"); a >= 0) {
      normals = view(a, what + " NORMAL", TINYGLTF_TYPE_VEC3, false);
      if (normals->count != positions.count) fail(what + " has a NORMAL count different from its POSITION count");
    }
    if (int a = attribute("TEXCOORD_0"); a >= 0) {
      uvs = view(a, what + " TEXCOORD_0", TINYGLTF_TYPE_VEC2, true);
      if (uvs->count != positions.count) fail(what + " has a TEXCOORD_0 count different from its POSITION count");
    }
    if (primitive.indices >= 0)
      indices = view(primitive.indices, what + " indices", TINYGLTF_TYPE_SCALAR, false, true);
    limitZeroAccessors({&positions, normals ? &*normals : nullptr, uvs ? &*uvs : nullptr,
                        indices ? &*indices : nullptr});

    out.positions.resize(positions.count);
    for (size_t i = 0; i < positions.count; ++i)
      out.positions[i] = Vec3f(positions.component(i, 0), positions.component(i, 1), positions.component(i, 2));
    if (normals) {
      out.normals.resize(normals->count);
      for (size_t i = 0; i < normals->count; ++i)
        out.normals[i] = Vec3f(normals->component(i, 0), normals->component(i, 1), normals->component(i, 2));
    }
    if (uvs) {
      out.uvs.resize(uvs->count);
      for (size_t i = 0; i < uvs->count; ++i) out.uvs[i] = Vec2f(uvs->component(i, 0), uvs->component(i, 1));
    }
    if (indices) {
      out.indices.resize(indices->count);
      for (size_t i = 0; i < indices->count; ++i) out.indices[i] = indices->index(i);
    } else {  // non-indexed: consecutive vertex triples
      out.indices.resize(positions.count);
      for (size_t i = 0; i < positions.count; ++i) out.indices[i] = uint32_t(i);
    }
    if (out.indices.size() % 3 != 0)
      fail(what + " has " + std::to_string(out.indices.size()) + " vertex indices, which is not a multiple of 3");
  }

  // An accessor without a buffer view is all zeros (glTF 3.6.2.1), so a file of a few
  // hundred bytes can declare billions of elements. Such an accessor may hold no more
  // elements than the largest accessor of the same primitive that has data: those were
  // checked against the bytes present, which bounds every allocation by the file's size.
  void limitZeroAccessors(std::initializer_list<const AccessorView*> views) const {
    size_t withData = 0;
    for (const AccessorView* v : views)
      if (v && v->data) withData = std::max(withData, v->count);
    for (const AccessorView* v : views)
      if (v && !v->data && v->count > withData)
        fail(v->name + " has no buffer view (all zeros) and " + std::to_string(v->count) +
             " elements, more than the " + std::to_string(withData) +
             " of the largest accessor with data in its primitive");
  }

  // Checks an accessor's type, component type and extent. Vertex data must be float
  // (normalized unsigned byte/short also allowed where `normalizedOk`, as glTF allows for
  // TEXCOORD); indices must be unsigned byte, short or int.
  AccessorView view(int index, const std::string& what, int type, bool normalizedOk, bool isIndex = false) const {
    if (index < 0 || index >= int(model_.accessors.size()))
      fail(what + " refers to accessor " + std::to_string(index) + " but the file has " +
           std::to_string(model_.accessors.size()));
    const tinygltf::Accessor& a = model_.accessors[index];
    const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    if (a.sparse.isSparse) fail(name + " is sparse; Glint does not support sparse accessors");
    int ct = a.componentType;
    bool okComponent =
        isIndex ? (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                   ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                : (ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                   (normalizedOk && a.normalized &&
                    (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
    if (a.type != type || !okComponent)
      fail(name + " has an unsupported type or component type (" +
           (isIndex ? "expected unsigned byte, short or int scalars)"
                    : normalizedOk ? "expected float, or normalized unsigned byte or short)" : "expected float)"));
    AccessorView v;
    v.name = name;
    v.count = a.count;
    v.componentType = ct;
    v.normalized = a.normalized;
    if (a.bufferView < 0) return v;  // glTF 3.6.2.1: no buffer view means all zeros
    if (a.bufferView >= int(model_.bufferViews.size()))
      fail(name + " refers to buffer view " + std::to_string(a.bufferView) + ", which does not exist");
    const tinygltf::BufferView& bv = model_.bufferViews[a.bufferView];
    const std::string viewName = "buffer view " + std::to_string(a.bufferView);
    if (bv.buffer < 0 || bv.buffer >= int(model_.buffers.size()))
      fail(viewName + " refers to a buffer that does not exist");
    const tinygltf::Buffer& buffer = model_.buffers[bv.buffer];
    // Offsets and lengths are the file's 64-bit numbers: every bound below is checked by
    // subtraction from what is present, since a sum can wrap around 2^64 and pass.
    size_t bufferSize = buffer.data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset)
      fail(viewName + " (" + std::to_string(bv.byteLength) + " bytes from byte " + std::to_string(bv.byteOffset) +
           ") extends past the end of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(bufferSize) +
           " bytes)");
    int stride = a.ByteStride(bv);
    size_t elementSize =
        size_t(tinygltf::GetComponentSizeInBytes(uint32_t(ct))) * tinygltf::GetNumComponentsInType(uint32_t(type));
    if (stride <= 0 || size_t(stride) < elementSize) fail(name + " has an invalid byte stride");
    v.stride = size_t(stride);
    // The last element, at byteOffset + stride * (count - 1), must end inside the view.
    bool fits = a.byteOffset <= bv.byteLength;
    if (fits && a.count > 0) {
      size_t room = bv.byteLength - a.byteOffset;
      fits = elementSize <= room && a.count - 1 <= (room - elementSize) / v.stride;
    }
    if (!fits)
      fail(name + " reads past the end of " + viewName + " (" + std::to_string(a.count) + " elements from byte " +
           std::to_string(a.byteOffset) + " of " + std::to_string(bv.byteLength) + ")");
    v.data = buffer.data.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  // Scene material for a glTF material index (-1: the primitive has none), converted once.
  int material(int index) {
    auto [it, inserted] = materials_.try_emplace(index, int(scene_.materials.size()));
    if (inserted) scene_.materials.push_back(index < 0 ? defaultMaterial() : convertMaterial(index));
    return it->second;
  }

  // glTF 2.0 section 3.9.6: a primitive without a material uses "a material with no
  // properties specified", i.e. every default: white base colour, metallic 1, roughness 1
  // (a rough white metal). Glint follows the specification rather than the grey plastic
  // some viewers substitute, so that renders match conforming viewers.
  static Material defaultMaterial() {
    Material m;
    m.name = "glTF default material";
    m.baseColor = Rgb(1.0f);
    m.metallic = 1.0f;
    m.roughness = 1.0f;
    return m;
  }

  Material convertMaterial(int index) {
    if (index >= int(model_.materials.size()))
      fail("refers to material " + std::to_string(index) + " but the file has " +
           std::to_string(model_.materials.size()));
    const tinygltf::Material& g = model_.materials[index];
    Material m;
    m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
    // tinygltf fills the glTF defaults (factor 1, metallic 1, roughness 1) for a missing
    // pbrMetallicRoughness block, as the specification prescribes.
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    m.baseColor = rgbOr(pbr.baseColorFactor, Rgb(1.0f));  // alpha ignored: no transparency
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    m.baseColorTexture = texture(pbr.baseColorTexture, true, m.name);
    m.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture, false, m.name);

    const tinygltf::Value* emissive = findExtension(g.extensions, "KHR_materials_emissive_strength");
    float strength = float(numberOr(emissive, "emissiveStrength", 1.0));
    m.emission = rgbOr(g.emissiveFactor, Rgb(0.0f)) * strength;
    m.emissionTexture = texture(g.emissiveTexture, true, m.name);

    // KHR_materials_specular: dielectric F0 = F0(ior) * specularColorFactor * specularFactor,
    // with F0(ior) = ((ior - 1) / (ior + 1))^2 from KHR_materials_ior (0.04 at the default
    // ior 1.5). Glint's dielectric F0 is 0.08 * specularLevel * specularTint, hence the
    // level below (0.5 for a plain glTF material).
    const tinygltf::Value* specular = findExtension(g.extensions, "KHR_materials_specular");
    double specularFactor = numberOr(specular, "specularFactor", 1.0);
    double ior = std::max(1.0, numberOr(findExtension(g.extensions, "KHR_materials_ior"), "ior", 1.5));
    double f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
    m.specularLevel = float(0.5 * specularFactor * f0 / 0.04);
    m.specularTint = rgbOr(specular, "specularColorFactor", Rgb(1.0f));
    if (specular && (specular->Has("specularTexture") || specular->Has("specularColorTexture")))
      warnOnce("KHR_materials_specular textures are ignored (their factors are used)");

    if (g.alphaMode == "BLEND") warnOnce("alphaMode BLEND is ignored: transparency is not supported");
    if (g.alphaMode == "MASK") warnOnce("alphaMode MASK is ignored: alpha cut-outs are not supported");
    if (g.normalTexture.index >= 0 || g.occlusionTexture.index >= 0)
      warnOnce("normal and occlusion textures are ignored");
    return m;
  }

  // Scene texture for a material slot, or -1. Each (image, colour space) pair is decoded
  // once, so an image used both as colour and as data gets one copy of each.
  int texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& material) {
    if (info.index < 0) return -1;
    if (info.index >= int(model_.textures.size()))
      fail("material '" + material + "' refers to texture " + std::to_string(info.index) + " but the file has " +
           std::to_string(model_.textures.size()));
    if (info.texCoord != 0) {
      warnOnce("textures on TEXCOORD_" + std::to_string(info.texCoord) +
               " are ignored: only TEXCOORD_0 is supported");
      return -1;
    }
    if (info.extensions.count("KHR_texture_transform"))
      warnOnce("KHR_texture_transform is ignored: textures are applied untransformed");
    const tinygltf::Texture& t = model_.textures[info.index];
    if (t.sampler >= 0 && t.sampler < int(model_.samplers.size())) {
      const tinygltf::Sampler& s = model_.samplers[t.sampler];
      if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
        warnOnce("texture wrap modes other than REPEAT are ignored: all textures repeat");
    }
    if (t.source < 0 || t.source >= int(model_.images.size()))
      fail("texture " + std::to_string(info.index) + " has no image Glint can decode (PNG or JPEG)");
    auto [it, inserted] = textures_.try_emplace({t.source, srgb}, int(scene_.textures.size()));
    if (inserted) scene_.textures.push_back(convertImage(t.source, srgb));
    return it->second;
  }

  // 8- or 16-bit image with 1 to 4 channels -> float Texture: grey (+alpha) becomes one
  // channel, RGB(A) three; alpha is dropped since transparency is not supported.
  Texture convertImage(int index, bool srgb) const {
    const tinygltf::Image& g = model_.images[index];
    std::string label = "image " + std::to_string(index);
    if (!g.uri.empty() && g.uri.rfind("data:", 0) != 0) label += " (" + g.uri + ")";
    if (g.image.empty() || g.width <= 0 || g.height <= 0)
      fail(label + " could not be decoded" + (loaderWarnings_.empty() ? "" : ": " + loaderWarnings_));
    if (g.bits != 8 && g.bits != 16)
      fail(label + " has " + std::to_string(g.bits) + " bits per channel; only 8 and 16 are supported");
    if (g.component < 1 || g.component > 4)
      fail(label + " has " + std::to_string(g.component) + " channels; only 1 to 4 are supported");
    size_t bytes = size_t(g.bits / 8);
    size_t pixels = size_t(g.width) * size_t(g.height);
    if (g.image.size() < pixels * g.component * bytes) fail(label + " has fewer pixel bytes than its size requires");

    // One lookup table per bit depth turns every stored value into linear float.
    size_t levels = size_t(1) << g.bits;
    std::vector<float> decode(levels);
    for (size_t v = 0; v < levels; ++v) {
      float x = float(v) / float(levels - 1);
      decode[v] = srgb ? srgbToLinear(x) : x;
    }
    Texture t;
    t.name = (g.name.empty() ? label : g.name) + (srgb ? "" : " (linear)");
    int channels = g.component >= 3 ? 3 : 1;
    t.image = Image(g.width, g.height, channels);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < channels; ++c) {
        const unsigned char* src = g.image.data() + (p * g.component + c) * bytes;
        size_t raw = bytes == 1 ? *src : AccessorView::load<uint16_t>(src);  // stb returns native order
        t.image.pixels[p * channels + c] = decode[raw];
      }
    return t;
  }

  // KHR_lights_punctual. glTF states intensities in photometric units (candela for point
  // and spot, lux for directional); Glint uses the numbers directly as radiometric W/sr and
  // W/m^2, without the 683 lm/W luminous-efficacy conversion, so that scenes exported from
  // Blender keep roughly the brightness they had there. Range is ignored (lights follow
  // the inverse-square law to infinity).
  void addLight(const tinygltf::Node& node, const Mat4& world) {
    const tinygltf::Value* ext = findExtension(node.extensions, "KHR_lights_punctual");
    if (!ext || !ext->Has("light")) return;
    int index = ext->Get("light").GetNumberAsInt();
    if (index < 0 || index >= int(model_.lights.size()))
      fail("node '" + node.name + "' refers to light " + std::to_string(index) + " but the file has " +
           std::to_string(model_.lights.size()));
    const tinygltf::Light& g = model_.lights[index];
    PunctualLight light;
    if (g.type == "point") light.type = PunctualLight::Type::Point;
    else if (g.type == "spot") light.type = PunctualLight::Type::Spot;
    else if (g.type == "directional") light.type = PunctualLight::Type::Directional;
    else fail("light " + std::to_string(index) + " has unknown type '" + g.type + "'");
    // Lights sit at the node origin and shine down the node's -Z axis.
    light.position = Vec3f(world.transformPoint(Vec3d(0.0)));
    light.direction = Vec3f(normalize(world.transformVector(Vec3d(0, 0, -1))));
    light.intensity = rgbOr(g.color, Rgb(1.0f)) * float(g.intensity);
    light.innerConeAngle = float(g.spot.innerConeAngle);
    light.outerConeAngle = float(g.spot.outerConeAngle);
    scene_.lights.push_back(light);
  }

  std::filesystem::path path_;
  std::string source_;
  tinygltf::Model model_;
  std::string loaderWarnings_;
  MeshScene scene_;
  std::map<int, int> materials_;                 // glTF material (-1: none) -> scene material
  std::map<std::pair<int, bool>, int> textures_;  // (glTF image, sRGB) -> scene texture
  std::set<std::string> warned_;
  int skippedPrimitives_ = 0;
};

}  // namespace

MeshScene loadGltfScene(const std::filesystem::path& path) { return GltfImporter(path).run(); }

}  // namespace glint
