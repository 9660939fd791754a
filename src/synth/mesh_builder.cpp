// Procedural mesh construction.
#include "synth/mesh_builder.h"

#include <cmath>

#include "math/sampling.h"

namespace glint {

TriangleMesh makeQuad(const std::string& name, const Vec3f& corner, const Vec3f& u, const Vec3f& v, int material,
                      float uvScale) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  mesh.positions = {corner, corner + u, corner + u + v, corner + v};
  Vec3f n = normalize(cross(u, v));
  mesh.normals = {n, n, n, n};
  mesh.uvs = {{0, 0}, {uvScale, 0}, {uvScale, uvScale}, {0, uvScale}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

TriangleMesh makeBox(const std::string& name, const Vec3f& lo, const Vec3f& hi, int material) {
  TriangleMesh box;
  box.name = name;
  box.material = material;
  Vec3f d = hi - lo;
  // Each face spanned so that u x v points outwards.
  appendMesh(box, makeQuad("", {lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}, material));   // +z
  appendMesh(box, makeQuad("", {hi.x, lo.y, lo.z}, {-d.x, 0, 0}, {0, d.y, 0}, material));  // -z
  appendMesh(box, makeQuad("", {hi.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}, material));  // +x
  appendMesh(box, makeQuad("", {lo.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, material));   // -x
  appendMesh(box, makeQuad("", {lo.x, hi.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}, material));  // +y
  appendMesh(box, makeQuad("", {lo.x, lo.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, material));   // -y
  return box;
}

TriangleMesh makeCylinder(const std::string& name, const Vec3f& base, float radius, float height, int segments,
                          int material) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  // Side: two rings of vertices with radial normals.
  for (int i = 0; i <= segments; ++i) {
    float phi = 2 * kPi * float(i) / segments;
    Vec3f n(std::cos(phi), 0, std::sin(phi));
    for (int ring = 0; ring < 2; ++ring) {
      mesh.positions.push_back(base + n * radius + Vec3f(0, ring * height, 0));
      mesh.normals.push_back(n);
      mesh.uvs.push_back({float(i) / segments, float(ring)});
    }
  }
  for (int i = 0; i < segments; ++i) {
    uint32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    // Winding with outward geometric normals.
    mesh.indices.insert(mesh.indices.end(), {a, b, c, c, b, d});
  }
  // Caps as fans.
  for (int cap = 0; cap < 2; ++cap) {
    float y = cap * height;
    Vec3f n(0, cap ? 1.0f : -1.0f, 0);
    uint32_t centre = uint32_t(mesh.positions.size());
    mesh.positions.push_back(base + Vec3f(0, y, 0));
    mesh.normals.push_back(n);
    mesh.uvs.push_back({0.5f, 0.5f});
    for (int i = 0; i <= segments; ++i) {
      float phi = 2 * kPi * float(i) / segments;
      mesh.positions.push_back(base + Vec3f(radius * std::cos(phi), y, radius * std::sin(phi)));
      mesh.normals.push_back(n);
      mesh.uvs.push_back({0.5f + 0.5f * std::cos(phi), 0.5f + 0.5f * std::sin(phi)});
    }
    for (int i = 0; i < segments; ++i) {
      uint32_t p = centre + 1 + i, q = centre + 2 + i;
      if (cap) mesh.indices.insert(mesh.indices.end(), {centre, q, p});
      else mesh.indices.insert(mesh.indices.end(), {centre, p, q});
    }
  }
  return mesh;
}

TriangleMesh makeUvSphere(const std::string& name, const Vec3f& center, float radius, int segments, int rings,
                          int material) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  for (int r = 0; r <= rings; ++r) {
    float theta = kPi * float(r) / rings;
    for (int s = 0; s <= segments; ++s) {
      float phi = 2 * kPi * float(s) / segments;
      Vec3f n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(center + n * radius);
      mesh.normals.push_back(n);
      mesh.uvs.push_back({float(s) / segments, float(r) / rings});
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  return mesh;
}

void appendMesh(TriangleMesh& a, const TriangleMesh& b) {
  uint32_t offset = uint32_t(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  a.uvs.insert(a.uvs.end(), b.uvs.begin(), b.uvs.end());
  for (uint32_t i : b.indices) a.indices.push_back(i + offset);
}

Texture makeCheckerTexture(const std::string& name, const Rgb& a, const Rgb& b, int squares, int pixelsPerSquare) {
  Texture texture;
  texture.name = name;
  int size = squares * pixelsPerSquare;
  texture.image = Image(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      bool odd = ((x / pixelsPerSquare) + (y / pixelsPerSquare)) % 2 == 1;
      texture.image.setRgb(x, y, odd ? b : a);
    }
  return texture;
}

}  // namespace glint
