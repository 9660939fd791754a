// Reading, validating and writing edit files. Every problem is reported as
// `FILE: LOCATION: problem`, LOCATION being the JSON path (`operations[2].axis`), so the user
// can find the mistake without guessing.
#include "edit/edit_file.h"

#include <cmath>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/printable_text.h"
#include "io/json_file.h"

namespace glint {

namespace {

using nlohmann::json;

constexpr const char* kVersionKey = "glint_edits";

const char* attributeName(Attribute a) {
  switch (a) {
    case Attribute::F0: return "f0";
    case Attribute::Roughness: return "roughness";
    case Attribute::Diffuse: return "diffuse";
    case Attribute::Metalness: return "metalness";
  }
  return "?";
}

}  // namespace

const char* operationName(Operation::Kind k) {
  switch (k) {
    case Operation::Kind::Translate: return "translate";
    case Operation::Kind::Rotate: return "rotate";
    case Operation::Kind::Scale: return "scale";
    case Operation::Kind::Duplicate: return "duplicate";
    case Operation::Kind::Delete: return "delete";
    case Operation::Kind::Roughness: return "roughness";
    case Operation::Kind::F0: return "f0";
    case Operation::Kind::Diffuse: return "diffuse";
  }
  return "?";
}

namespace {

const char* combinationName(Selection::Kind k) {
  switch (k) {
    case Selection::Kind::Union: return "union";
    case Selection::Kind::Intersection: return "intersection";
    case Selection::Kind::Difference: return "difference";
    default: return "?";
  }
}

// Reads one document; `fail` prefixes the source and the JSON location.
class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  EditDocument document(const json& j) {
    if (!j.is_object()) fail("", "must be a JSON object with \"glint_edits\", \"selections\" and \"operations\"");
    allowOnly(j, "", {kVersionKey, "selections", "operations"});
    auto version = j.find(kVersionKey);
    if (version == j.end()) fail("", "missing \"glint_edits\": 1 (the edit file version)");
    if (!version->is_number_integer() || version->get<long long>() != EditDocument::kVersion)
      fail(kVersionKey, "unsupported version " + printableText(version->dump()) + " (this Glint reads version 1)");

    EditDocument doc;
    doc.source = source_;
    if (auto s = j.find("selections"); s != j.end()) {
      if (!s->is_object()) fail("selections", "must be an object of named selections");
      for (auto it = s->begin(); it != s->end(); ++it) {
        if (it.key().empty()) fail("selections", "a selection name must not be empty");
        doc.selections[it.key()] = selection(*it, "selections." + it.key());
      }
    }
    checkOperandsAndCycles(doc);

    auto ops = j.find("operations");
    if (ops == j.end()) fail("", "missing \"operations\" (a list, applied in order)");
    if (!ops->is_array()) fail("operations", "must be a list of operations");
    for (size_t i = 0; i < ops->size(); ++i)
      doc.operations.push_back(operation((*ops)[i], "operations[" + std::to_string(i) + "]", doc));
    return doc;
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
    // Names and keys are the file's own strings, which may hold control characters.
    throw Error(source_, printableText(where.empty() ? problem : where + ": " + problem, std::string::npos));
  }

  void allowOnly(const json& object, const std::string& where, std::initializer_list<const char*> keys) const {
    for (auto it = object.begin(); it != object.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) {
        std::string list;
        for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(where, "unknown key \"" + it.key() + "\" (expected " + list + ")");
      }
    }
  }

  static std::string at(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

  const json& required(const json& object, const std::string& where, const char* key) const {
    auto it = object.find(key);
    if (it == object.end()) fail(where, std::string("missing \"") + key + "\"");
    return *it;
  }

  // A finite number that also fits a float (1e39 would become infinity).
  float number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "must be a number, not " + std::string(j.type_name()));
    double d = j.get<double>();
    if (!std::isfinite(d) || !std::isfinite(float(d))) fail(where, "must be a finite number");
    return float(d);
  }

  std::vector<float> numbers(const json& j, const std::string& where, size_t count) const {
    if (!j.is_array() || j.size() != count)
      fail(where, "must be a list of " + std::to_string(count) + " numbers");
    std::vector<float> v;
    for (size_t i = 0; i < count; ++i) v.push_back(number(j[i], where + "[" + std::to_string(i) + "]"));
    return v;
  }

  Vec3f vec3(const json& j, const std::string& where) const {
    auto v = numbers(j, where, 3);
    return {v[0], v[1], v[2]};
  }

  Vec2f vec2(const json& j, const std::string& where) const {
    auto v = numbers(j, where, 2);
    return {v[0], v[1]};
  }

  // Stored as written (normalised on use, like every quaternion in Glint); must not be zero.
  Quatf rotation(const json& j, const std::string& where) const {
    auto v = numbers(j, where, 4);
    Quatf q{v[0], v[1], v[2], v[3]};
    if (!(q.norm() > 1e-6f)) fail(where, "a rotation quaternion [w, x, y, z] must not be zero");
    return q;
  }

  Shape box(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "must be an object with min/max or center/half_extent");
    Shape s;
    s.kind = Shape::Kind::Box;
    if (j.contains("min") || j.contains("max")) {
      allowOnly(j, where, {"min", "max"});
      Vec3f lo = vec3(required(j, where, "min"), at(where, "min"));
      Vec3f hi = vec3(required(j, where, "max"), at(where, "max"));
      for (int a = 0; a < 3; ++a)
        if (lo[a] > hi[a]) fail(where, "min must not exceed max (axis " + std::to_string(a) + ")");
      s.center = (lo + hi) * 0.5f;
      s.halfExtent = (hi - lo) * 0.5f;
      return s;
    }
    allowOnly(j, where, {"center", "half_extent", "rotation"});
    s.center = vec3(required(j, where, "center"), at(where, "center"));
    s.halfExtent = vec3(required(j, where, "half_extent"), at(where, "half_extent"));
    if (s.halfExtent.x < 0 || s.halfExtent.y < 0 || s.halfExtent.z < 0)
      fail(at(where, "half_extent"), "must not be negative");
    if (j.contains("rotation")) s.rotation = rotation(j["rotation"], at(where, "rotation"));
    return s;
  }

  Shape sphere(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "must be an object with center and radius");
    allowOnly(j, where, {"center", "radius"});
    Shape s;
    s.kind = Shape::Kind::Sphere;
    s.center = vec3(required(j, where, "center"), at(where, "center"));
    s.radius = number(required(j, where, "radius"), at(where, "radius"));
    if (s.radius < 0) fail(at(where, "radius"), "must not be negative");
    return s;
  }

  Shape cylinder(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "must be an object with center, radii and half_height");
    allowOnly(j, where, {"center", "radii", "half_height", "rotation"});
    Shape s;
    s.kind = Shape::Kind::Cylinder;
    s.center = vec3(required(j, where, "center"), at(where, "center"));
    s.radii = vec2(required(j, where, "radii"), at(where, "radii"));
    // Zero radii would divide by zero in the inside test.
    if (!(s.radii.x > 0 && s.radii.y > 0)) fail(at(where, "radii"), "must be positive");
    s.halfHeight = number(required(j, where, "half_height"), at(where, "half_height"));
    if (s.halfHeight < 0) fail(at(where, "half_height"), "must not be negative");
    if (j.contains("rotation")) s.rotation = rotation(j["rotation"], at(where, "rotation"));
    return s;
  }

  std::vector<AttributeFilter> filters(const json& j, const std::string& where) const {
    if (!j.is_array()) fail(where, "must be a list of {\"attribute\": ..., \"range\": [lo, hi]}");
    std::vector<AttributeFilter> out;
    for (size_t i = 0; i < j.size(); ++i) {
      std::string here = where + "[" + std::to_string(i) + "]";
      const json& f = j[i];
      if (!f.is_object()) fail(here, "must be an object {\"attribute\": ..., \"range\": [lo, hi]}");
      allowOnly(f, here, {"attribute", "range"});
      const json& name = required(f, here, "attribute");
      AttributeFilter filter;
      bool known = false;
      for (Attribute a : {Attribute::F0, Attribute::Roughness, Attribute::Diffuse, Attribute::Metalness})
        if (name.is_string() && name.get<std::string>() == attributeName(a)) filter.attribute = a, known = true;
      if (!known) fail(at(here, "attribute"), "unknown attribute " + printableText(name.dump()) + " (f0, roughness, diffuse or metalness)");
      Vec2f range = vec2(required(f, here, "range"), at(here, "range"));
      if (range.x > range.y) fail(at(here, "range"), "lo must not exceed hi");
      filter.lo = range.x;
      filter.hi = range.y;
      out.push_back(filter);
    }
    return out;
  }

  std::vector<std::string> operands(const json& j, const std::string& where, size_t minimum) const {
    if (!j.is_array() || j.size() < minimum)
      fail(where, "must be a list of at least " + std::to_string(minimum) + " selection name(s)");
    std::vector<std::string> names;
    for (size_t i = 0; i < j.size(); ++i) {
      if (!j[i].is_string()) fail(where + "[" + std::to_string(i) + "]", "must be a selection name");
      names.push_back(j[i].get<std::string>());
    }
    return names;
  }

  Selection selection(const json& j, const std::string& where) const {
    Selection s;
    if (j.is_string()) {
      if (j.get<std::string>() != "everything")
        fail(where, "unknown selection " + printableText(j.dump()) + " (only \"everything\" may be written as a string)");
      s.kind = Selection::Kind::Everything;
      return s;
    }
    if (!j.is_object()) fail(where, "must be an object or \"everything\"");
    allowOnly(j, where,
              {"box", "sphere", "cylinder", "everything", "union", "intersection", "difference", "filters", "grow"});
    int kinds = 0;
    for (const char* k : {"box", "sphere", "cylinder", "everything", "union", "intersection", "difference"})
      kinds += j.contains(k);
    if (kinds != 1)
      fail(where, "must have exactly one of box, sphere, cylinder, everything, union, intersection, difference");
    if (j.contains("box")) {
      s.kind = Selection::Kind::Shape, s.shape = box(j["box"], at(where, "box"));
    } else if (j.contains("sphere")) {
      s.kind = Selection::Kind::Shape, s.shape = sphere(j["sphere"], at(where, "sphere"));
    } else if (j.contains("cylinder")) {
      s.kind = Selection::Kind::Shape, s.shape = cylinder(j["cylinder"], at(where, "cylinder"));
    } else if (j.contains("everything")) {
      if (j["everything"] != true) fail(at(where, "everything"), "must be true");
      s.kind = Selection::Kind::Everything;
    } else if (j.contains("union")) {
      s.kind = Selection::Kind::Union, s.operands = operands(j["union"], at(where, "union"), 1);
    } else if (j.contains("intersection")) {
      s.kind = Selection::Kind::Intersection, s.operands = operands(j["intersection"], at(where, "intersection"), 1);
    } else {
      // The first operand minus the others: one operand alone would subtract nothing.
      s.kind = Selection::Kind::Difference, s.operands = operands(j["difference"], at(where, "difference"), 2);
    }
    if (j.contains("filters")) s.filters = filters(j["filters"], at(where, "filters"));
    if (j.contains("grow")) s.grow = growth(j["grow"], at(where, "grow"));
    return s;
  }

  SelectionGrowth growth(const json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "must be an object {\"distance\": d, \"tolerance\": t}");
    allowOnly(j, where, {"distance", "tolerance"});
    SelectionGrowth g;
    g.distance = number(required(j, where, "distance"), at(where, "distance"));
    if (!(g.distance > 0 && g.distance <= 1e3f)) fail(at(where, "distance"), "must lie in (0, 1000]");
    if (j.contains("tolerance")) g.tolerance = number(j["tolerance"], at(where, "tolerance"));
    if (!(g.tolerance >= 0 && g.tolerance <= 1)) fail(at(where, "tolerance"), "must lie in [0, 1]");
    return g;
  }

  // Every operand names a selection, and no selection contains itself.
  void checkOperandsAndCycles(const EditDocument& doc) const {
    for (const auto& [name, s] : doc.selections)
      for (const std::string& operand : s.operands)
        if (!doc.selections.count(operand))
          fail("selections." + name + "." + combinationName(s.kind), "unknown selection \"" + operand + "\"");
    // Depth-first, with an explicit stack: a chain of 10^5 selections must neither overflow
    // the call stack nor copy the chain at every level. The chain is spelt out only for a cycle.
    enum class Mark { Unvisited, Visiting, Done };
    std::map<std::string, Mark> marks;
    struct Visit {
      const std::string* name;
      size_t nextOperand = 0;
    };
    for (const auto& [start, unused] : doc.selections) {
      if (marks[start] == Mark::Done) continue;
      std::vector<Visit> stack{{&start}};
      marks[start] = Mark::Visiting;
      while (!stack.empty()) {
        Visit& top = stack.back();
        const std::vector<std::string>& operands = doc.selections.at(*top.name).operands;
        if (top.nextOperand == operands.size()) {
          marks[*top.name] = Mark::Done;
          stack.pop_back();
          continue;
        }
        const std::string& operand = operands[top.nextOperand++];
        Mark& mark = marks[operand];
        if (mark == Mark::Visiting) {
          std::string chain;
          bool inCycle = false;
          for (const Visit& v : stack) {
            inCycle = inCycle || *v.name == operand;
            if (inCycle) chain += *v.name + " -> ";
          }
          fail("selections", "selections refer to each other in a cycle: " + chain + operand);
        }
        if (mark == Mark::Unvisited) {
          mark = Mark::Visiting;
          stack.push_back({&operand});
        }
      }
    }
  }

  // Exactly one of `modes` must be present; returns its index.
  int oneOf(const json& j, const std::string& where, std::initializer_list<const char*> modes) const {
    int found = -1, index = 0, count = 0;
    std::string list;
    for (const char* m : modes) {
      if (j.contains(m)) found = index, ++count;
      list += (list.empty() ? "" : ", ") + std::string(m);
      ++index;
    }
    if (count != 1) fail(where, "needs exactly one of " + list);
    return found;
  }

  ColorChange color(const json& j, const std::string& where, bool isF0) const {
    ColorChange c;
    int mode = oneOf(j, where, {"set", "hsv_shift", "hsv_multiply"});
    if (mode == 0) {
      c.mode = ColorChange::Mode::Set;
      c.value = vec3(j["set"], at(where, "set"));
      for (int i = 0; i < 3; ++i) {
        if (c.value[i] < 0) fail(at(where, "set"), "colour components must not be negative");
        if (isF0 && c.value[i] > 1) fail(at(where, "set"), "F0 components must be in [0, 1]");
      }
      if (j.contains("blend")) {
        c.blend = number(j["blend"], at(where, "blend"));
        if (c.blend < 0 || c.blend > 1) fail(at(where, "blend"), "must be in [0, 1]");
      }
      return c;
    }
    if (j.contains("blend")) fail(at(where, "blend"), "only applies to \"set\"");
    if (mode == 1) {
      c.mode = ColorChange::Mode::HsvShift;
      c.value = vec3(j["hsv_shift"], at(where, "hsv_shift"));
    } else {
      c.mode = ColorChange::Mode::HsvMultiply;
      c.value = vec3(j["hsv_multiply"], at(where, "hsv_multiply"));
      if (c.value.x < 0 || c.value.y < 0 || c.value.z < 0)
        fail(at(where, "hsv_multiply"), "factors must not be negative");
    }
    return c;
  }

  Operation operation(const json& j, const std::string& where, const EditDocument& doc) const {
    if (!j.is_object()) fail(where, "must be an object {\"op\": ..., \"selection\": ..., ...}");
    const json& opName = required(j, where, "op");
    Operation op;
    bool known = false;
    for (auto k : {Operation::Kind::Translate, Operation::Kind::Rotate, Operation::Kind::Scale,
                   Operation::Kind::Duplicate, Operation::Kind::Delete, Operation::Kind::Roughness,
                   Operation::Kind::F0, Operation::Kind::Diffuse})
      if (opName.is_string() && opName.get<std::string>() == operationName(k)) op.kind = k, known = true;
    if (!known)
      fail(where, "unknown operation " + printableText(opName.dump()) +
                      " (translate, rotate, scale, duplicate, delete, roughness, f0 or diffuse)");
    const json& selectionName = required(j, where, "selection");
    if (!selectionName.is_string()) fail(at(where, "selection"), "must be the name of a selection");
    op.selection = selectionName.get<std::string>();
    auto selection = doc.selections.find(op.selection);
    if (selection == doc.selections.end()) fail(at(where, "selection"), "unknown selection \"" + op.selection + "\"");

    auto readPivot = [&] {
      if (j.contains("pivot")) {
        op.hasPivot = true;
        op.pivot = vec3(j["pivot"], at(where, "pivot"));
      } else if (selection->second.kind != Selection::Kind::Shape) {
        fail(where, "needs a \"pivot\": selection \"" + op.selection + "\" has no shape whose centre could serve");
      }
    };
    switch (op.kind) {
      case Operation::Kind::Translate:
      case Operation::Kind::Duplicate:
        allowOnly(j, where, {"op", "selection", "offset"});
        op.offset = vec3(required(j, where, "offset"), at(where, "offset"));
        break;
      case Operation::Kind::Rotate:
        allowOnly(j, where, {"op", "selection", "axis", "angle_degrees", "pivot"});
        op.axis = vec3(required(j, where, "axis"), at(where, "axis"));
        if (!(length(op.axis) > 1e-6f)) fail(at(where, "axis"), "must not be zero");
        op.angleDegrees = number(required(j, where, "angle_degrees"), at(where, "angle_degrees"));
        readPivot();
        break;
      case Operation::Kind::Scale:
        allowOnly(j, where, {"op", "selection", "factor", "pivot"});
        op.factor = number(required(j, where, "factor"), at(where, "factor"));
        if (!(op.factor > 0)) fail(at(where, "factor"), "must be positive");
        readPivot();
        break;
      case Operation::Kind::Delete:
        allowOnly(j, where, {"op", "selection"});
        break;
      case Operation::Kind::Roughness: {
        allowOnly(j, where, {"op", "selection", "set", "shift", "multiply"});
        int mode = oneOf(j, where, {"set", "shift", "multiply"});
        const char* key = mode == 0 ? "set" : mode == 1 ? "shift" : "multiply";
        op.roughnessMode = mode == 0   ? Operation::RoughnessMode::Set
                           : mode == 1 ? Operation::RoughnessMode::Shift
                                       : Operation::RoughnessMode::Multiply;
        op.amount = number(j[key], at(where, key));
        if (mode == 0 && (op.amount < 0 || op.amount > 1)) fail(at(where, key), "must be in [0, 1]");
        if (mode == 2 && op.amount < 0) fail(at(where, key), "must not be negative");
        break;
      }
      case Operation::Kind::F0:
      case Operation::Kind::Diffuse:
        allowOnly(j, where, {"op", "selection", "set", "blend", "hsv_shift", "hsv_multiply"});
        op.color = color(j, where, op.kind == Operation::Kind::F0);
        break;
    }
    return op;
  }

  std::string source_;
};

json vec(const Vec3f& v) { return json::array({v.x, v.y, v.z}); }

json shapeToJson(const Shape& s) {
  bool rotated = !(s.rotation.w == 1 && s.rotation.x == 0 && s.rotation.y == 0 && s.rotation.z == 0);
  json rotation = json::array({s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z});
  switch (s.kind) {
    case Shape::Kind::Box: {
      json box = {{"center", vec(s.center)}, {"half_extent", vec(s.halfExtent)}};
      if (rotated) box["rotation"] = rotation;
      return {{"box", box}};
    }
    case Shape::Kind::Sphere:
      return {{"sphere", {{"center", vec(s.center)}, {"radius", s.radius}}}};
    case Shape::Kind::Cylinder: {
      json cylinder = {{"center", vec(s.center)},
                       {"radii", json::array({s.radii.x, s.radii.y})},
                       {"half_height", s.halfHeight}};
      if (rotated) cylinder["rotation"] = rotation;
      return {{"cylinder", cylinder}};
    }
  }
  return {};
}

json selectionToJson(const Selection& s) {
  json j;
  switch (s.kind) {
    case Selection::Kind::Everything:
      if (s.filters.empty()) return "everything";
      j = {{"everything", true}};
      break;
    case Selection::Kind::Shape: j = shapeToJson(s.shape); break;
    default: j = {{combinationName(s.kind), s.operands}}; break;
  }
  if (!s.filters.empty()) {
    json filters = json::array();
    for (const AttributeFilter& f : s.filters)
      filters.push_back({{"attribute", attributeName(f.attribute)}, {"range", {f.lo, f.hi}}});
    j["filters"] = filters;
  }
  if (s.grow.distance > 0) j["grow"] = {{"distance", s.grow.distance}, {"tolerance", s.grow.tolerance}};
  return j;
}

json operationToJson(const Operation& op) {
  json j = {{"op", operationName(op.kind)}, {"selection", op.selection}};
  switch (op.kind) {
    case Operation::Kind::Translate:
    case Operation::Kind::Duplicate: j["offset"] = vec(op.offset); break;
    case Operation::Kind::Rotate:
      j["axis"] = vec(op.axis);
      j["angle_degrees"] = op.angleDegrees;
      if (op.hasPivot) j["pivot"] = vec(op.pivot);
      break;
    case Operation::Kind::Scale:
      j["factor"] = op.factor;
      if (op.hasPivot) j["pivot"] = vec(op.pivot);
      break;
    case Operation::Kind::Delete: break;
    case Operation::Kind::Roughness: {
      const char* key = op.roughnessMode == Operation::RoughnessMode::Set     ? "set"
                        : op.roughnessMode == Operation::RoughnessMode::Shift ? "shift"
                                                                              : "multiply";
      j[key] = op.amount;
      break;
    }
    case Operation::Kind::F0:
    case Operation::Kind::Diffuse:
      switch (op.color.mode) {
        case ColorChange::Mode::Set:
          j["set"] = vec(op.color.value);
          j["blend"] = op.color.blend;
          break;
        case ColorChange::Mode::HsvShift: j["hsv_shift"] = vec(op.color.value); break;
        case ColorChange::Mode::HsvMultiply: j["hsv_multiply"] = vec(op.color.value); break;
      }
      break;
  }
  return j;
}

}  // namespace

EditDocument parseEditDocument(const nlohmann::json& json, const std::string& source) {
  return Parser(source).document(json);
}

EditDocument readEditFile(const std::filesystem::path& path) {
  return parseEditDocument(readJsonFile(path), path.string());
}

nlohmann::json editDocumentToJson(const EditDocument& document) {
  json selections = json::object();
  for (const auto& [name, s] : document.selections) selections[name] = selectionToJson(s);
  json operations = json::array();
  for (const Operation& op : document.operations) operations.push_back(operationToJson(op));
  return {{kVersionKey, EditDocument::kVersion}, {"selections", selections}, {"operations", operations}};
}

void writeEditFile(const std::filesystem::path& path, const EditDocument& document) {
  writeTextAtomically(path, editDocumentToJson(document).dump(2) + "\n");
}

}  // namespace glint
