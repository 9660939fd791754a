// Horizontal layers of flat Gaussians for the render tests: a regular grid of nearly opaque
// discs standing in for a plane (mirror floors, emitting ceilings, small patterns), and a
// pair of facing mirrors.
#pragma once

#include <cmath>

#include "scene/gaussians.h"

namespace glint::test {

// Material and shape of every Gaussian of a layer.
struct LayerLook {
  Rgb diffuse{0.0f};
  Vec3f normal{0, 0, 1};
  float roughness = 1.0f;
  Rgb f0{0.0f};
  float opacity = 0.98f;
  // Standard deviation in the plane, as a fraction of the grid spacing: 0.8 overlaps the
  // neighbours enough for the layer to be opaque between centres.
  float sigmaPerSpacing = 0.8f;
  float thickness = 0.004f;  // standard deviation along z
};

// Adds countX x countY Gaussians at height z on a grid of the given spacing, centred on
// (centreX, centreY): the layer's nominal extent is countX x spacing by countY x spacing.
inline void addLayer(GaussianScene* scene, float centreX, float centreY, float z, int countX, int countY,
                     float spacing, const LayerLook& look) {
  float sigma = look.sigmaPerSpacing * spacing;
  for (int i = 0; i < countX; ++i)
    for (int j = 0; j < countY; ++j) {
      size_t k = scene->size();
      scene->resize(k + 1);
      scene->position[k] = Vec3f(centreX + spacing * (float(i) + 0.5f - 0.5f * float(countX)),
                                 centreY + spacing * (float(j) + 0.5f - 0.5f * float(countY)), z);
      scene->logScale[k] = Vec3f(std::log(sigma), std::log(sigma), std::log(look.thickness));
      scene->opacityLogit[k] = logit(look.opacity);
      scene->diffuse[k] = look.diffuse;
      scene->normal[k] = look.normal;
      scene->roughness[k] = look.roughness;
      scene->f0[k] = look.f0;
    }
}

// Two facing glossy mirrors 3 m apart, a reddish floor at z = 0 and a bluish ceiling at
// z = 3, each 4 x 4 m: paths bounce between them and every reflected segment sees colour.
inline GaussianScene facingMirrors() {
  GaussianScene scene;
  addLayer(&scene, 0.0f, 0.0f, 0.0f, 41, 41, 0.1f, {Rgb(0.3f, 0.1f, 0.1f), Vec3f(0, 0, 1), 0.1f, Rgb(0.8f)});
  addLayer(&scene, 0.0f, 0.0f, 3.0f, 41, 41, 0.1f, {Rgb(0.1f, 0.1f, 0.4f), Vec3f(0, 0, -1), 0.1f, Rgb(0.7f)});
  return scene;
}

// A 1 m floor (diffuse 0.3) at z = 0 under a 9.6 m emitting ceiling (2.0) at z = 1.5, with a
// black 0.3 m plate at plateHeight (none at 0) shading the floor's centre: the room of the
// relighting tests. The Gaussians are ceiling, floor, plate, in that order.
struct PlateRoom {
  GaussianScene scene;
  size_t floorBegin = 0, floorEnd = 0;  // the floor's index range
  size_t centre = 0;                    // the floor Gaussian nearest the centre, under the plate
};

inline PlateRoom plateRoom(float plateHeight = 0.4f) {
  PlateRoom room;
  LayerLook ceiling;
  ceiling.diffuse = Rgb(2.0f);
  ceiling.normal = Vec3f(0, 0, -1);
  addLayer(&room.scene, 0, 0, 1.5f, 24, 24, 0.4f, ceiling);
  room.floorBegin = room.scene.size();
  LayerLook floor;
  floor.diffuse = Rgb(0.3f);
  addLayer(&room.scene, 0, 0, 0, 10, 10, 0.1f, floor);
  room.floorEnd = room.scene.size();
  if (plateHeight > 0) {
    LayerLook plate;
    plate.normal = Vec3f(0, 0, -1);
    addLayer(&room.scene, 0, 0, plateHeight, 6, 6, 0.05f, plate);
  }
  room.centre = room.floorBegin;
  for (size_t i = room.floorBegin; i < room.floorEnd; ++i)
    if (length(room.scene.position[i]) < length(room.scene.position[room.centre])) room.centre = i;
  return room;
}

}  // namespace glint::test
