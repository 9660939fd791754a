// Point-in-shape tests, derived metalness and attribute filters for edit selections.
#include "edit/shape.h"

#include <algorithm>
#include <cmath>

namespace glint {

bool shapeContains(const Shape& shape, const Vec3f& p) {
  // Into the shape's local frame: the rotation's columns are the local axes in world space.
  Vec3f local = quatToRotation(shape.rotation).transposeTimes(p - shape.center);
  switch (shape.kind) {
    case Shape::Kind::Box:
      return std::abs(local.x) <= shape.halfExtent.x && std::abs(local.y) <= shape.halfExtent.y &&
             std::abs(local.z) <= shape.halfExtent.z;
    case Shape::Kind::Sphere:
      return dot(local, local) <= shape.radius * shape.radius;
    case Shape::Kind::Cylinder: {
      if (std::abs(local.y) > shape.halfHeight) return false;
      float u = local.x / shape.radii.x, v = local.z / shape.radii.y;
      return u * u + v * v <= 1.0f;
    }
  }
  return false;
}

float derivedMetalness(float meanDiffuse, float meanF0) {
  float specular = std::max(meanF0 - 0.04f, 0.0f);
  float denominator = specular + std::max(meanDiffuse, 0.0f);
  if (denominator <= 0.0f) return 0.0f;
  return std::clamp(specular / denominator, 0.0f, 1.0f);
}

bool filterAccepts(const AttributeFilter& filter, const Rgb& F0, float roughness, const Rgb& diffuse) {
  auto mean = [](const Rgb& c) { return (c.x + c.y + c.z) / 3.0f; };
  float value = 0.0f;
  switch (filter.attribute) {
    case Attribute::F0: value = mean(F0); break;
    case Attribute::Roughness: value = roughness; break;
    case Attribute::Diffuse: value = mean(diffuse); break;
    case Attribute::Metalness: value = derivedMetalness(mean(diffuse), mean(F0)); break;
  }
  return value >= filter.lo && value <= filter.hi;
}

}  // namespace glint
