// A tiny ground-truth mesh scene and edit-document helpers shared by the mesh edit tests.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "edit/edit_document.h"
#include "synth/mesh_scene.h"

namespace glint::test {

// Materials: 0 "paint" (dielectric, shared by the triangle and sphere B), 1 "chrome" (metal,
// roughness 0.05), 2 "gold" (metal, roughness 0.4).
// Nodes: 0 the triangle (0,0,0) (1,0,0) (0,1,0), normals +Z, bounds centre (0.5, 0.5, 0);
// 1 sphere A at (2, 0, 0) r 0.5 chrome; 2 sphere B at (4, 0, 0) r 1 paint; 3 sphere C at
// (0, 3, 0) r 0.25 gold.
inline MeshScene tinyMeshScene() {
  MeshScene scene;
  Material paint;
  paint.name = "paint";
  paint.baseColor = {0.2f, 0.4f, 0.6f};
  paint.roughness = 0.6f;
  Material chrome;
  chrome.name = "chrome";
  chrome.baseColor = {0.9f, 0.6f, 0.5f};
  chrome.metallic = 1.0f;
  chrome.roughness = 0.05f;
  Material gold;
  gold.name = "gold";
  gold.baseColor = {1.0f, 0.77f, 0.34f};
  gold.metallic = 1.0f;
  gold.roughness = 0.4f;
  scene.materials = {paint, chrome, gold};
  TriangleMesh triangle;
  triangle.name = "triangle";
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  triangle.indices = {0, 1, 2};
  triangle.material = 0;
  scene.meshes = {triangle};
  scene.spheres = {{{2, 0, 0}, 0.5f, 1}, {{4, 0, 0}, 1.0f, 0}, {{0, 3, 0}, 0.25f, 2}};
  return scene;
}

inline Selection boxSelection(Vec3f center, Vec3f halfExtent, std::vector<AttributeFilter> filters = {}) {
  Selection s;
  s.kind = Selection::Kind::Shape;
  s.shape.kind = Shape::Kind::Box;
  s.shape.center = center;
  s.shape.halfExtent = halfExtent;
  s.filters = std::move(filters);
  return s;
}

inline Selection everything(std::vector<AttributeFilter> filters = {}) {
  Selection s;
  s.kind = Selection::Kind::Everything;
  s.filters = std::move(filters);
  return s;
}

inline Selection combination(Selection::Kind kind, std::vector<std::string> operands) {
  Selection s;
  s.kind = kind;
  s.operands = std::move(operands);
  return s;
}

}  // namespace glint::test
