// Writes small glTF 2.0 test files by hand (.gltf with embedded or external buffers, .glb)
// and tiny uncompressed PNGs, so importer tests do not depend on any exporter.
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace glint::test {

using Bytes = std::vector<uint8_t>;

inline void writeBytes(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), std::streamsize(size));
}

inline std::string base64(const Bytes& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= bytes[i + 2];
    size_t left = bytes.size() - i;
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += left > 1 ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += left > 2 ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

// PNG (ISO/IEC 15948) with one IDAT holding a zlib stream of stored (uncompressed) deflate
// blocks (RFC 1950/1951). `samples` are row-major, channels interleaved; 16-bit samples
// are given as values and written big-endian as PNG requires.
inline Bytes encodePng(int width, int height, int channels, int bitDepth, const std::vector<uint16_t>& samples) {
  auto crc32 = [](const uint8_t* p, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
      c ^= p[i];
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto put32 = [](Bytes& b, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) b.push_back(uint8_t(v >> s));
  };
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  auto chunk = [&](const char* type, const Bytes& data) {
    put32(png, uint32_t(data.size()));
    Bytes typed(type, type + 4);
    typed.insert(typed.end(), data.begin(), data.end());
    png.insert(png.end(), typed.begin(), typed.end());
    put32(png, crc32(typed.data(), typed.size()));
  };
  const uint8_t colorType[] = {0, 0, 4, 2, 6};  // grey, grey+alpha, RGB, RGBA
  Bytes header;
  put32(header, uint32_t(width));
  put32(header, uint32_t(height));
  header.insert(header.end(), {uint8_t(bitDepth), colorType[channels], 0, 0, 0});
  chunk("IHDR", header);

  Bytes raw;  // each row: filter type 0, then the samples
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    for (int i = 0; i < width * channels; ++i) {
      uint16_t v = samples[size_t(y) * width * channels + i];
      if (bitDepth == 16) raw.push_back(uint8_t(v >> 8));
      raw.push_back(uint8_t(v));
    }
  }
  Bytes zlib = {0x78, 0x01};
  for (size_t at = 0; at == 0 || at < raw.size(); at += 65535) {
    size_t n = std::min<size_t>(65535, raw.size() - at);
    zlib.push_back(at + n >= raw.size() ? 1 : 0);  // BFINAL, BTYPE = stored
    zlib.insert(zlib.end(), {uint8_t(n), uint8_t(n >> 8), uint8_t(~n), uint8_t(~n >> 8)});
    zlib.insert(zlib.end(), raw.begin() + at, raw.begin() + at + n);
  }
  uint32_t a = 1, b = 0;  // Adler-32
  for (uint8_t v : raw) a = (a + v) % 65521, b = (b + a) % 65521;
  put32(zlib, (b << 16) | a);
  chunk("IDAT", zlib);
  chunk("IEND", {});
  return png;
}

// Builds the JSON and the single binary buffer of a glTF file.
struct GltfBuilder {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  Bytes bin;

  static int append(nlohmann::json& array, nlohmann::json item) {
    array.push_back(std::move(item));
    return int(array.size()) - 1;
  }
  int add(const char* section, nlohmann::json item) { return append(doc[section], std::move(item)); }

  // Appends raw bytes (4-byte aligned) as a new buffer view.
  int addView(const void* data, size_t size, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (stride) view["byteStride"] = stride;
    bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
    return add("bufferViews", view);
  }
  template <typename T>
  int addView(const std::vector<T>& values, size_t stride = 0) {
    return addView(values.data(), values.size() * sizeof(T), stride);
  }
  int addAccessor(int view, int componentType, size_t count, const char* type, size_t offset = 0,
                  bool normalized = false) {
    nlohmann::json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (offset) a["byteOffset"] = offset;
    if (normalized) a["normalized"] = true;
    return add("accessors", a);
  }
  // A PNG stored in the binary buffer, wrapped in an image and a texture; returns the texture.
  int addPngTexture(const Bytes& png) {
    int image = add("images", {{"bufferView", addView(png)}, {"mimeType", "image/png"}});
    return add("textures", {{"source", image}});
  }

  // The buffer entry depends on the container, so it is filled in when writing.
  void writeEmbedded(const std::filesystem::path& path) {
    doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    std::ofstream(path) << doc.dump(1);
  }
  void writeExternal(const std::filesystem::path& path, const std::string& binName) {
    doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", binName}}};
    writeBytes(path.parent_path() / binName, bin.data(), bin.size());
    std::ofstream(path) << doc.dump(1);
  }
  // GLB (glTF 2.0 section 4.4): 12-byte header, a JSON chunk padded with spaces, a BIN
  // chunk padded with zeros; all little-endian.
  void writeGlb(const std::filesystem::path& path) {
    doc["buffers"] = {{{"byteLength", bin.size()}}};
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    Bytes data = bin;
    while (data.size() % 4) data.push_back(0);
    Bytes out;
    auto put32 = [&](uint32_t v) {
      for (int s = 0; s < 32; s += 8) out.push_back(uint8_t(v >> s));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    put32(2);
    put32(uint32_t(12 + 8 + json.size() + 8 + data.size()));
    put32(uint32_t(json.size()));
    put32(0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    put32(uint32_t(data.size()));
    put32(0x004E4942u);  // "BIN\0"
    out.insert(out.end(), data.begin(), data.end());
    writeBytes(path, out.data(), out.size());
  }
};

constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kFloat = 5126;  // glTF componentType

// A unit quad in the z = 0 plane facing +Z: two counter-clockwise triangles whose
// positions, normals and UVs are interleaved in one buffer view (32-byte stride).
inline int addQuadMesh(GltfBuilder& b, int material = -1) {
  struct Vertex {
    float p[3], n[3], uv[2];
  };
  std::vector<Vertex> v = {{{0, 0, 0}, {0, 0, 1}, {0, 1}},
                           {{1, 0, 0}, {0, 0, 1}, {1, 1}},
                           {{1, 1, 0}, {0, 0, 1}, {1, 0}},
                           {{0, 1, 0}, {0, 0, 1}, {0, 0}}};
  int view = b.addView(v, sizeof(Vertex));
  nlohmann::json attributes = {{"POSITION", b.addAccessor(view, kFloat, 4, "VEC3", 0)},
                     {"NORMAL", b.addAccessor(view, kFloat, 4, "VEC3", 12)},
                     {"TEXCOORD_0", b.addAccessor(view, kFloat, 4, "VEC2", 24)}};
  std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
  nlohmann::json primitive = {{"attributes", attributes},
                    {"indices", b.addAccessor(b.addView(indices), kUnsignedShort, 6, "SCALAR")}};
  if (material >= 0) primitive["material"] = material;
  return b.add("meshes", {{"name", "Quad"}, {"primitives", {primitive}}});
}

}  // namespace glint::test
