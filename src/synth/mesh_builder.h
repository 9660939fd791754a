// Procedural meshes for the built-in scenes and tests: quads, boxes, cylinders, spheres.
#pragma once

#include "synth/mesh_scene.h"

namespace glint {

// A parallelogram with corner `corner` spanned by edges u and v; normal = normalize(u x v).
// Texture coordinates run 0..uvScale along each edge.
TriangleMesh makeQuad(const std::string& name, const Vec3f& corner, const Vec3f& u, const Vec3f& v, int material,
                      float uvScale = 1.0f);

// An axis-aligned box with outward normals (flat shaded, 24 vertices).
TriangleMesh makeBox(const std::string& name, const Vec3f& lower, const Vec3f& upper, int material);

// A capped cylinder along +Y from base centre, with smooth side normals.
TriangleMesh makeCylinder(const std::string& name, const Vec3f& baseCenter, float radius, float height, int segments,
                          int material);

// A UV sphere with smooth normals (for glTF-like tessellated content; exact spheres use Sphere).
TriangleMesh makeUvSphere(const std::string& name, const Vec3f& center, float radius, int segments, int rings,
                          int material);

// Appends b to a (same material).
void appendMesh(TriangleMesh& a, const TriangleMesh& b);

// A checkerboard texture: `squares` squares per side, each `pixelsPerSquare` texels.
Texture makeCheckerTexture(const std::string& name, const Rgb& a, const Rgb& b, int squares, int pixelsPerSquare);

}  // namespace glint
