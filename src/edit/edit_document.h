// The in-memory form of an edit file (docs/edit-files.md): named selections and an ordered
// list of operations. Both the Gaussian side (edit/gaussian_edits) and the mesh side
// (synth_edit/mesh_edits, for `glint synth --edits`) apply the same document.
#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

#include "math/quat.h"
#include "math/vec.h"

namespace glint {

// A region of space. Every shape has a centre and an orientation (identity = axis aligned);
// the box is given by its half extents along its local axes, the elliptic cylinder by its
// radii along local x and z and its half height along local y.
struct Shape {
  enum class Kind { Box, Sphere, Cylinder };
  Kind kind = Kind::Box;
  Vec3f center{0.0f};
  Quatf rotation;           // local-to-world orientation
  Vec3f halfExtent{0.0f};   // Box
  float radius = 0.0f;      // Sphere
  Vec2f radii{0.0f, 0.0f};  // Cylinder: along local x and local z
  float halfHeight = 0.0f;  // Cylinder: along local y
};

// Per-primitive attributes a filter can test (means over the RGB channels).
enum class Attribute { F0, Roughness, Diffuse, Metalness };

struct AttributeFilter {
  Attribute attribute = Attribute::Roughness;
  float lo = 0.0f, hi = 1.0f;  // inclusive range
};

// Growth of a Gaussian selection along connected Gaussians of similar material, e.g. to
// take with an object the cap of it that a selection box stopping above the floor leaves
// behind: repeatedly, a Gaussian joins when its centre lies within `distance` of a selected
// one whose mean diffuse, mean F0 and roughness each differ from its own by at most
// `tolerance`. distance 0: no growth. Meshes (`glint synth --edits`) are selected whole and
// do not grow.
struct SelectionGrowth {
  float distance = 0.0f;
  float tolerance = 0.1f;
};

// A named selection: a shape, everything, or a combination of other named selections;
// then every filter must hold, then the selection grows (SelectionGrowth). Difference is
// the first operand minus all the others.
struct Selection {
  enum class Kind { Shape, Everything, Union, Intersection, Difference };
  Kind kind = Kind::Everything;
  Shape shape;                         // Kind::Shape
  std::vector<std::string> operands;   // Union, Intersection, Difference
  std::vector<AttributeFilter> filters;
  SelectionGrowth grow;
};

// How a colour (diffuse or F0) is changed: replaced (mixed with `blend` in [0, 1]),
// shifted in HSV (hue in degrees, saturation and value additive), or multiplied in HSV.
struct ColorChange {
  enum class Mode { Set, HsvShift, HsvMultiply };
  Mode mode = Mode::Set;
  Rgb value{0.0f};  // Set: the colour; HsvShift / HsvMultiply: (h, s, v)
  float blend = 1.0f;
};

// One operation on one named selection. Selections are evaluated against the scene as it
// stands when the operation runs (after the operations before it).
struct Operation {
  enum class Kind {
    Translate,  // offset
    Rotate,     // axis, angleDegrees, pivot
    Scale,      // factor, pivot
    Duplicate,  // offset: the copies are appended, moved by offset
    Delete,
    Roughness,  // roughnessMode and amount
    F0,         // color
    Diffuse,    // color
  };
  enum class RoughnessMode { Set, Shift, Multiply };

  Kind kind = Kind::Translate;
  std::string selection;
  Vec3f offset{0.0f};
  Vec3f axis{0.0f, 1.0f, 0.0f};
  float angleDegrees = 0.0f;
  float factor = 1.0f;
  // Rotate and Scale turn about this point; absent in the file = the centre of the
  // selection's shape (an error for selections without one).
  bool hasPivot = false;
  Vec3f pivot{0.0f};
  RoughnessMode roughnessMode = RoughnessMode::Set;
  float amount = 0.0f;
  ColorChange color;
};

struct EditDocument {
  static constexpr int kVersion = 1;  // "glint_edits": 1
  std::string source;  // where it came from (the file), for errors found while applying it
  std::map<std::string, Selection> selections;
  std::vector<Operation> operations;
};

// The point a rotate or scale turns about: its pivot, or else the centre of its selection's
// shape (parseEditDocument guarantees one of the two exists).
inline Vec3f operationPivot(const EditDocument& document, const Operation& op) {
  if (op.hasPivot) return op.pivot;
  auto it = document.selections.find(op.selection);
  return it != document.selections.end() && it->second.kind == Selection::Kind::Shape ? it->second.shape.center
                                                                                       : Vec3f(0.0f);
}

}  // namespace glint
