// Edit files: the documented example parses, a document using every feature survives a
// write/read round trip exactly, and malformed files are rejected with one message naming
// the file, the JSON location and the problem.
#include "edit/edit_file.h"

#include <gtest/gtest.h>

#include "common/expect_error.h"
#include "core/atomic_file.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

using nlohmann::json;

// The example of docs/edit-files.md, kept identical so the specification stays valid.
const char* kDocumentedExample = R"({
  "glint_edits": 1,
  "selections": {
    "chrome":  {"box": {"min": [-1.2, 0.0, -0.4], "max": [-0.4, 0.8, 0.4]},
                "filters": [{"attribute": "roughness", "range": [0.0, 0.1]}]},
    "tilted":  {"box": {"center": [0, 1, 0], "half_extent": [0.5, 0.2, 0.5], "rotation": [0.966, 0, 0.259, 0]}},
    "ball":    {"sphere": {"center": [0, 0.5, 0], "radius": 0.6}},
    "can":     {"cylinder": {"center": [0, 0.5, 0], "radii": [0.3, 0.2], "half_height": 0.5}},
    "all":     "everything",
    "both":    {"union": ["chrome", "ball"]},
    "overlap": {"intersection": ["chrome", "ball"]},
    "rest":    {"difference": ["all", "chrome"]}
  },
  "operations": [
    {"op": "translate", "selection": "chrome", "offset": [0.3, 0, 0]},
    {"op": "rotate",    "selection": "tilted", "axis": [0, 1, 0], "angle_degrees": 30, "pivot": [0, 1, 0]},
    {"op": "scale",     "selection": "ball", "factor": 1.5},
    {"op": "duplicate", "selection": "ball", "offset": [1, 0, 0]},
    {"op": "delete",    "selection": "overlap"},
    {"op": "roughness", "selection": "ball", "set": 0.05},
    {"op": "roughness", "selection": "ball", "shift": 0.1},
    {"op": "roughness", "selection": "ball", "multiply": 0.5},
    {"op": "f0",        "selection": "ball", "set": [0.95, 0.64, 0.54], "blend": 1.0},
    {"op": "diffuse",   "selection": "ball", "hsv_shift": [120, 0, 0]},
    {"op": "diffuse",   "selection": "ball", "hsv_multiply": [1, 0.5, 1.2]}
  ]
})";

TEST(EditFile, ReadsTheDocumentedExample) {
  EditDocument doc = parseEditDocument(json::parse(kDocumentedExample), "example");
  ASSERT_EQ(doc.selections.size(), 8u);
  ASSERT_EQ(doc.operations.size(), 11u);
  const Selection& chrome = doc.selections.at("chrome");
  EXPECT_EQ(chrome.kind, Selection::Kind::Shape);
  EXPECT_EQ(chrome.shape.kind, Shape::Kind::Box);
  EXPECT_NEAR(chrome.shape.center.x, -0.8f, 1e-6f);
  EXPECT_NEAR(chrome.shape.halfExtent.y, 0.4f, 1e-6f);
  ASSERT_EQ(chrome.filters.size(), 1u);
  EXPECT_EQ(chrome.filters[0].attribute, Attribute::Roughness);
  EXPECT_EQ(chrome.filters[0].hi, 0.1f);
  EXPECT_EQ(doc.selections.at("all").kind, Selection::Kind::Everything);
  EXPECT_EQ(doc.selections.at("rest").kind, Selection::Kind::Difference);
  EXPECT_EQ(doc.selections.at("rest").operands, (std::vector<std::string>{"all", "chrome"}));
  EXPECT_EQ(doc.selections.at("can").shape.radii.y, 0.2f);
  EXPECT_EQ(doc.operations[1].kind, Operation::Kind::Rotate);
  EXPECT_TRUE(doc.operations[1].hasPivot);
  EXPECT_FALSE(doc.operations[2].hasPivot);  // the sphere's centre
  EXPECT_EQ(doc.operations[6].roughnessMode, Operation::RoughnessMode::Shift);
  EXPECT_EQ(doc.operations[9].color.mode, ColorChange::Mode::HsvShift);
  EXPECT_EQ(doc.operations[10].color.value.z, 1.2f);
}

// A document with every selection kind, every filter and every operation mode.
EditDocument everyFeature() {
  EditDocument doc;
  Selection box;
  box.kind = Selection::Kind::Shape;
  box.shape.kind = Shape::Kind::Box;
  box.shape.center = {0.1f, 0.2f, 0.3f};
  box.shape.halfExtent = {1.0f, 0.5f, 0.25f};
  box.shape.rotation = Quatf{0.9f, 0.1f, 0.3f, -0.2f};
  box.filters = {{Attribute::F0, 0.5f, 1.0f}, {Attribute::Metalness, 0.7f, 1.0f}};
  doc.selections["box"] = box;
  Selection sphere;
  sphere.kind = Selection::Kind::Shape;
  sphere.shape.kind = Shape::Kind::Sphere;
  sphere.shape.center = {-1.0f, 0.5f, 2.0f};
  sphere.shape.radius = 0.7f;
  sphere.filters = {{Attribute::Roughness, 0.0f, 0.125f}};
  doc.selections["sphere"] = sphere;
  Selection cylinder;
  cylinder.kind = Selection::Kind::Shape;
  cylinder.shape.kind = Shape::Kind::Cylinder;
  cylinder.shape.center = {0.0f, 1.0f, 0.0f};
  cylinder.shape.radii = {0.3f, 0.6f};
  cylinder.shape.halfHeight = 0.45f;
  cylinder.shape.rotation = Quatf{0.0f, 1.0f, 0.0f, 0.0f};
  doc.selections["cylinder"] = cylinder;
  Selection all;
  all.kind = Selection::Kind::Everything;
  doc.selections["all"] = all;
  all.filters = {{Attribute::Diffuse, 0.2f, 0.9f}};
  all.grow = {0.05f, 0.2f};
  doc.selections["bright"] = all;
  Selection combination;
  combination.kind = Selection::Kind::Union;
  combination.operands = {"box", "sphere"};
  doc.selections["union"] = combination;
  combination.kind = Selection::Kind::Intersection;
  combination.operands = {"union", "cylinder"};
  doc.selections["intersection"] = combination;
  combination.kind = Selection::Kind::Difference;
  combination.operands = {"all", "intersection", "bright"};
  combination.filters = {{Attribute::Roughness, 0.25f, 0.75f}};
  doc.selections["difference"] = combination;

  auto add = [&](Operation::Kind kind, const std::string& selection) -> Operation& {
    Operation op;
    op.kind = kind;
    op.selection = selection;
    doc.operations.push_back(op);
    return doc.operations.back();
  };
  add(Operation::Kind::Translate, "box").offset = {0.5f, -0.25f, 1.0f};
  Operation& rotate = add(Operation::Kind::Rotate, "sphere");
  rotate.axis = {1.0f, 1.0f, 0.0f};
  rotate.angleDegrees = 33.0f;
  Operation& rotatePivot = add(Operation::Kind::Rotate, "union");
  rotatePivot.axis = {0.0f, 0.0f, 2.0f};
  rotatePivot.angleDegrees = -90.0f;
  rotatePivot.hasPivot = true;
  rotatePivot.pivot = {1.0f, 2.0f, 3.0f};
  add(Operation::Kind::Scale, "cylinder").factor = 1.5f;
  Operation& scalePivot = add(Operation::Kind::Scale, "all");
  scalePivot.factor = 0.5f;
  scalePivot.hasPivot = true;
  scalePivot.pivot = {0.0f, -1.0f, 0.0f};
  add(Operation::Kind::Duplicate, "intersection").offset = {2.0f, 0.0f, 0.0f};
  add(Operation::Kind::Delete, "difference");
  for (auto mode : {Operation::RoughnessMode::Set, Operation::RoughnessMode::Shift, Operation::RoughnessMode::Multiply}) {
    Operation& r = add(Operation::Kind::Roughness, "bright");
    r.roughnessMode = mode;
    r.amount = mode == Operation::RoughnessMode::Shift ? -0.125f : 0.375f;
  }
  for (auto kind : {Operation::Kind::F0, Operation::Kind::Diffuse}) {
    Operation& set = add(kind, "box");
    set.color = {ColorChange::Mode::Set, {0.9f, 0.6f, 0.5f}, 0.25f};
    add(kind, "box").color = {ColorChange::Mode::HsvShift, {120.0f, -0.5f, 0.1f}, 1.0f};
    add(kind, "box").color = {ColorChange::Mode::HsvMultiply, {1.0f, 0.5f, 2.0f}, 1.0f};
  }
  return doc;
}

TEST(EditFile, RoundTripsEveryFeature) {
  test::TempFolder folder;
  EditDocument doc = everyFeature();
  writeEditFile(folder / "edits.json", doc);
  EditDocument back = readEditFile(folder / "edits.json");
  EXPECT_EQ(editDocumentToJson(back), editDocumentToJson(doc));

  ASSERT_EQ(back.selections.size(), doc.selections.size());
  const Shape& box = back.selections.at("box").shape;
  EXPECT_EQ(box.center, Vec3f(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(box.rotation.y, 0.3f);
  EXPECT_EQ(back.selections.at("box").filters[1].attribute, Attribute::Metalness);
  EXPECT_EQ(back.selections.at("cylinder").shape.radii.y, 0.6f);
  EXPECT_EQ(back.selections.at("cylinder").shape.rotation.x, 1.0f);
  EXPECT_EQ(back.selections.at("bright").kind, Selection::Kind::Everything);
  EXPECT_EQ(back.selections.at("bright").filters[0].lo, 0.2f);
  EXPECT_EQ(back.selections.at("bright").grow.distance, 0.05f);
  EXPECT_EQ(back.selections.at("bright").grow.tolerance, 0.2f);
  EXPECT_EQ(back.selections.at("box").grow.distance, 0.0f);
  EXPECT_EQ(back.selections.at("difference").operands.size(), 3u);
  EXPECT_EQ(back.selections.at("difference").filters[0].hi, 0.75f);
  ASSERT_EQ(back.operations.size(), doc.operations.size());
  for (size_t i = 0; i < doc.operations.size(); ++i) {
    const Operation& a = doc.operations[i];
    const Operation& b = back.operations[i];
    EXPECT_EQ(b.kind, a.kind) << i;
    EXPECT_EQ(b.selection, a.selection) << i;
    EXPECT_EQ(b.hasPivot, a.hasPivot) << i;
  }
  EXPECT_EQ(back.operations[1].axis, Vec3f(1.0f, 1.0f, 0.0f));
  EXPECT_EQ(back.operations[2].pivot, Vec3f(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(back.operations[4].factor, 0.5f);
  EXPECT_EQ(back.operations[8].amount, -0.125f);
  EXPECT_EQ(back.operations[10].color.blend, 0.25f);
  EXPECT_EQ(back.operations[15].color.mode, ColorChange::Mode::HsvMultiply);
  EXPECT_EQ(back.operations[15].color.value, Vec3f(1.0f, 0.5f, 2.0f));
}

// A small valid document; each malformed case changes one thing in it.
json validDocument() {
  return json::parse(R"({
    "glint_edits": 1,
    "selections": {
      "ball": {"sphere": {"center": [0, 0.5, 0], "radius": 0.6}},
      "all": "everything",
      "rest": {"difference": ["all", "ball"]}
    },
    "operations": [
      {"op": "translate", "selection": "ball", "offset": [0.3, 0, 0]},
      {"op": "rotate", "selection": "ball", "axis": [0, 1, 0], "angle_degrees": 30},
      {"op": "roughness", "selection": "rest", "set": 0.5}
    ]
  })");
}

struct Malformed {
  const char* name;
  std::function<void(json&)> corrupt;
  std::vector<std::string> details;  // expected in the message, beside the file name
};

TEST(EditFile, RejectsMalformedFilesNamingFileAndProblem) {
  std::vector<Malformed> cases = {
      {"missing version", [](json& j) { j.erase("glint_edits"); }, {"glint_edits"}},
      {"wrong version", [](json& j) { j["glint_edits"] = 2; }, {"glint_edits", "version 2"}},
      {"unknown top-level key", [](json& j) { j["operation"] = json::array(); }, {"unknown key \"operation\""}},
      {"unknown operation", [](json& j) { j["operations"][1]["op"] = "rotat"; },
       {"operations[1]", "unknown operation \"rotat\""}},
      {"unknown selection in operation", [](json& j) { j["operations"][0]["selection"] = "balll"; },
       {"operations[0].selection", "unknown selection \"balll\""}},
      {"unknown operand", [](json& j) { j["selections"]["rest"]["difference"][1] = "nothing"; },
       {"selections.rest.difference", "unknown selection \"nothing\""}},
      {"selection cycle",
       [](json& j) {
         j["selections"]["a"] = {{"union", {"b"}}};
         j["selections"]["b"] = {{"intersection", {"ball", "a"}}};
       },
       {"cycle", "a -> b -> a"}},
      {"offset of two numbers", [](json& j) { j["operations"][0]["offset"] = {0.3, 0}; },
       {"operations[0].offset", "list of 3 numbers"}},
      {"string instead of number", [](json& j) { j["operations"][1]["angle_degrees"] = "30"; },
       {"operations[1].angle_degrees", "must be a number"}},
      {"number too large for a float", [](json& j) { j["operations"][0]["offset"][2] = 1e300; },
       {"operations[0].offset[2]", "finite"}},
      {"filter range lo > hi",
       [](json& j) { j["selections"]["ball"]["filters"] = {{{"attribute", "f0"}, {"range", {0.8, 0.2}}}}; },
       {"selections.ball.filters[0].range", "lo must not exceed hi"}},
      {"grow without distance", [](json& j) { j["selections"]["ball"]["grow"] = {{"tolerance", 0.1}}; },
       {"selections.ball.grow", "distance"}},
      {"grow distance zero", [](json& j) { j["selections"]["ball"]["grow"] = {{"distance", 0}}; },
       {"selections.ball.grow.distance", "(0, 1000]"}},
      {"grow tolerance above one",
       [](json& j) { j["selections"]["ball"]["grow"] = {{"distance", 0.1}, {"tolerance", 2}}; },
       {"selections.ball.grow.tolerance", "[0, 1]"}},
      {"unknown filter attribute",
       [](json& j) { j["selections"]["ball"]["filters"] = {{{"attribute", "shininess"}, {"range", {0, 1}}}}; },
       {"selections.ball.filters[0].attribute", "shininess"}},
      {"box min above max",
       [](json& j) { j["selections"]["ball"] = {{"box", {{"min", {0, 1, 0}}, {"max", {1, 0, 1}}}}}; },
       {"selections.ball.box", "min must not exceed max"}},
      {"negative radius", [](json& j) { j["selections"]["ball"]["sphere"]["radius"] = -1; },
       {"selections.ball.sphere.radius", "negative"}},
      {"zero cylinder radius",
       [](json& j) {
         j["selections"]["ball"] = {{"cylinder", {{"center", {0, 0, 0}}, {"radii", {0, 1}}, {"half_height", 1}}}};
       },
       {"selections.ball.cylinder.radii", "positive"}},
      {"zero rotation axis", [](json& j) { j["operations"][1]["axis"] = {0, 0, 0}; },
       {"operations[1].axis", "zero"}},
      {"blend outside [0, 1]",
       [](json& j) {
         j["operations"].push_back({{"op", "f0"}, {"selection", "ball"}, {"set", {1, 1, 1}}, {"blend", 1.5}});
       },
       {"operations[3].blend", "[0, 1]"}},
      {"scale factor zero",
       [](json& j) { j["operations"].push_back({{"op", "scale"}, {"selection", "ball"}, {"factor", 0}}); },
       {"operations[3].factor", "positive"}},
      {"rotate without pivot on a shapeless selection", [](json& j) { j["operations"][1]["selection"] = "rest"; },
       {"operations[1]", "pivot"}},
      {"two roughness modes", [](json& j) { j["operations"][2]["shift"] = 0.1; },
       {"operations[2]", "exactly one of set, shift, multiply"}},
      {"roughness set above 1", [](json& j) { j["operations"][2]["set"] = 1.5; },
       {"operations[2].set", "[0, 1]"}},
      {"unknown key in operation", [](json& j) { j["operations"][0]["offest"] = {1, 0, 0}; },
       {"operations[0]", "unknown key \"offest\""}},
      {"selection with two shapes",
       [](json& j) { j["selections"]["ball"]["box"] = {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}; },
       {"selections.ball", "exactly one of"}},
      {"operations not a list", [](json& j) { j["operations"] = {{"op", "delete"}}; },
       {"operations", "must be a list"}},
      {"F0 set above 1",
       [](json& j) { j["operations"].push_back({{"op", "f0"}, {"selection", "ball"}, {"set", {1.2, 1, 1}}}); },
       {"operations[3].set", "[0, 1]"}},
  };
  test::TempFolder folder;
  // The unmodified document is valid, so each failure below is due to its one change.
  writeTextAtomically(folder / "valid.json", validDocument().dump());
  EXPECT_NO_THROW(readEditFile(folder / "valid.json"));
  for (const Malformed& c : cases) {
    SCOPED_TRACE(c.name);
    json j = validDocument();
    c.corrupt(j);
    std::filesystem::path path = folder / "EDITS.json";
    writeTextAtomically(path, j.dump());
    for (const std::string& detail : c.details) test::expectErrorNaming([&] { readEditFile(path); }, path, detail);
  }
}

// JSON text cannot hold NaN (it is written as null), but a document built in memory can.
TEST(EditFile, RejectsNaNInMemoryDocuments) {
  json j = validDocument();
  j["operations"][0]["offset"][1] = std::nan("");
  test::expectErrorNaming([&] { parseEditDocument(j, "memory.json"); }, "memory.json",
                          {"operations[0].offset[1]", "finite"});
}

TEST(EditFile, RejectsBrokenJsonAndMissingFile) {
  test::TempFolder folder;
  writeTextAtomically(folder / "broken.json", "{\"glint_edits\": 1, ");
  test::expectErrorNaming([&] { readEditFile(folder / "broken.json"); }, folder / "broken.json", "not valid JSON");
  test::expectErrorNaming([&] { readEditFile(folder / "absent.json"); }, folder / "absent.json");
}

}  // namespace
}  // namespace glint
