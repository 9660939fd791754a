// `glint export` and 3DGS import end to end: refusal without --force, far-field removal and
// cropping with their counts, display-referred colour and SH degree, and --input-layout on
// every command that loads a scene; the exported display colour against Glint's own 8-bit
// render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/run_glint.h"
#include "io/image.h"
#include "io/ply.h"
#include "io/temp_folder.h"
#include "io/tonemap.h"
#include "scene/camera.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"
#include "train/scene_extent.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

// A scratch folder for one test, and the path of a file in it as a command-line argument.
class ExportCliTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  fs::path root() const { return folder_.path(); }

  test::TempFolder folder_;
};

// n Gaussians at the given positions, with colours from dark to bright.
GaussianScene sceneAt(const std::vector<Vec3f>& positions) {
  GaussianScene scene;
  scene.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    scene.position[i] = positions[i];
    scene.logScale[i] = {-3.0f, -4.0f, -5.0f};
    scene.diffuse[i] = Rgb(0.02f + 0.5f * float(i), 0.1f, 2.0f);
    scene.normal[i] = {0.0f, 0.0f, 1.0f};
    scene.roughness[i] = 0.3f;
  }
  return scene;
}

TEST_F(ExportCliTest, AnExistingOutputIsReplacedOnlyWithForce) {
  writeGaussianPly(path("scene.ply"), sceneAt({{0, 0, 0}, {1, 0, 0}}));
  const std::string command = "export " + path("scene.ply") + " -o " + path("out.ply");
  ASSERT_EQ(runGlint(command).status, 0);
  std::string before = test::readBytes(path("out.ply"));

  Outcome again = runGlint(command + " --sh-degree 3");
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("out.ply: already exists"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
  EXPECT_EQ(test::readBytes(path("out.ply")), before);

  Outcome forced = runGlint(command + " --sh-degree 3 --force");
  ASSERT_EQ(forced.status, 0) << forced.output;
  EXPECT_TRUE(readPly(path("out.ply")).has("f_rest_44"));
}

TEST_F(ExportCliTest, ColourShDegreeAndExposureReachTheFile) {
  GaussianScene scene = sceneAt({{0, 0, 0}, {1, 0, 0}, {0, 2, 0}});
  writeGaussianPly(path("scene.ply"), scene);
  Outcome run = runGlint("export " + path("scene.ply") + " -o " + path("display.ply") + " --exposure 2 --sh-degree 2");
  ASSERT_EQ(run.status, 0) << run.output;
  PlyTable table = readPly(path("display.ply"));
  EXPECT_TRUE(table.has("f_rest_23"));
  EXPECT_FALSE(table.has("f_rest_24"));
  for (size_t i = 0; i < scene.size(); ++i)
    EXPECT_NEAR(0.5 + kShC0 * table.column("f_dc_0")[i], tonemapFilmic(2.0f * scene.diffuse[i].x), 1e-6) << i;

  run = runGlint("export " + path("scene.ply") + " -o " + path("linear.ply") + " --colour linear --sh-degree 0");
  ASSERT_EQ(run.status, 0) << run.output;
  table = readPly(path("linear.ply"));
  EXPECT_FALSE(table.has("f_rest_0"));
  EXPECT_NEAR(0.5 + kShC0 * table.column("f_dc_2")[1], 2.0, 1e-6);  // above 1: linear is not clipped

  // Glint's own layout has no colour encoding or SH to choose.
  run = runGlint("export " + path("scene.ply") + " --format glint -o " + path("glint.ply") + " --sh-degree 1");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("do not apply to --format glint"), std::string::npos) << run.output;
  EXPECT_NE(runGlint("export " + path("scene.ply") + " -o " + path("x.ply") + " --sh-degree 4").status, 0);
  EXPECT_NE(runGlint("export " + path("scene.ply") + " -o " + path("x.ply") + " --exposure 0").status, 0);
  EXPECT_FALSE(fs::exists(path("x.ply")));
}

// What a 3DGS viewer shows of the export, 0.5 + C0 f_dc, is the colour of Glint's own 8-bit
// render (`glint render --format png`, the filmic tonemap) of the same Gaussians. Sampled at
// the projected centre of each of 12 opaque, separate Gaussians, whose colours run from
// near black to 6 times above the tonemap's knee, so clipping a linear export would show.
TEST_F(ExportCliTest, DisplayColourMatchesGlintsOwnEightBitRender) {
  const Camera camera = Camera::fromFieldOfView(Mat4::translation({0.0, 0.0, 3.0}), 0.9, 160, 120);
  std::ofstream(path("transforms_test.json"))
      << R"({"camera_angle_x": 0.9, "frames": [{"file_path": "test/render/render_0000", "transform_matrix": )"
      << R"([[1,0,0,0],[0,1,0,0],[0,0,1,3],[0,0,0,1]]}]})";
  GaussianScene scene;
  scene.resize(12);
  for (size_t i = 0; i < scene.size(); ++i) {
    scene.position[i] = {-1.05f + 0.7f * float(i % 4), -0.6f + 0.6f * float(i / 4), 0.0f};
    scene.logScale[i] = {std::log(0.09f), std::log(0.09f), std::log(0.002f)};
    scene.opacityLogit[i] = 9.0f;  // alpha 0.9999 at the centre
    const float level = 0.01f * std::pow(600.0f, float(i) / 11.0f);  // 0.01 .. 6
    scene.diffuse[i] = Rgb(level, 0.5f * level, std::min(1.0f, 3.0f * level));
    scene.normal[i] = {0.0f, 0.0f, 1.0f};
    scene.roughness[i] = 0.5f;
  }
  writeGaussianPly(path("scene.ply"), scene);
  Outcome exported = runGlint("export " + path("scene.ply") + " -o " + path("viewer.ply"));
  ASSERT_EQ(exported.status, 0) << exported.output;
  Outcome render = runGlint("render " + path("scene.ply") + " --dataset " + root().string() +
                            " --res 160x120 --bounces 0 --no-jitter --format png -o " + path("out"));
  ASSERT_EQ(render.status, 0) << render.output;

  const Image shown = readImage(root() / "out" / "render" / "render_0000.png");
  const PlyTable table = readPly(path("viewer.ply"));
  const Mat4 worldToCamera = camera.cameraToWorld.inverse();
  double sum = 0, worst = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    Vec2d pixel;
    ASSERT_TRUE(camera.project(worldToCamera, Vec3d(scene.position[i]), &pixel)) << i;
    const int x = int(pixel.x), y = int(pixel.y);
    for (int k = 0; k < 3; ++k) {
      const double viewer = 0.5 + kShC0 * table.column("f_dc_" + std::to_string(k))[i];
      const double difference = 255.0 * std::abs(std::clamp(viewer, 0.0, 1.0) - shown.at(x, y, k));
      sum += difference;
      worst = std::max(worst, difference);
    }
  }
  EXPECT_LE(sum / (3.0 * scene.size()), 1.0);  // within 1 level on average
  EXPECT_LE(worst, 2.0);
}

TEST_F(ExportCliTest, FarFieldIsDroppedAroundTheTrainingCamerasAndCropKeepsABox) {
  ASSERT_EQ(runGlint("synth builtin:spheres -o " + path("D") + " --train 3 --test 1 --res 8x6 --spp 1").status, 0);
  SceneSphere cameras = sceneSphere(Dataset::open(path("D"), false).split("train"));
  ASSERT_GT(cameras.radius, 0.0f);
  // Distances from the cameras' centre in units of S: 0, 1, 4.9 inside the default cut of
  // 5 S; 5.2, 12 and 30 outside it.
  std::vector<Vec3f> positions;
  for (float distance : {0.0f, 1.0f, 4.9f, 5.2f, 12.0f, 30.0f})
    positions.push_back(Vec3f(cameras.centre + Vec3d(0.0, 0.0, double(distance * cameras.radius))));
  writeGaussianPly(path("scene.ply"), sceneAt(positions));

  // A bare .ply names no cameras: everything is kept, and the output says why.
  Outcome bare = runGlint("export " + path("scene.ply") + " -o " + path("bare.ply"));
  ASSERT_EQ(bare.status, 0) << bare.output;
  EXPECT_NE(bare.output.find("far-field Gaussians kept"), std::string::npos) << bare.output;
  EXPECT_EQ(readPly(path("bare.ply")).count, 6u);

  Outcome dropped = runGlint("export " + path("scene.ply") + " -o " + path("near.ply") + " --dataset " + path("D"));
  ASSERT_EQ(dropped.status, 0) << dropped.output;
  EXPECT_NE(dropped.output.find("dropped 3 far-field Gaussians"), std::string::npos) << dropped.output;
  EXPECT_EQ(readPly(path("near.ply")).count, 3u);

  // A run folder's config.json names the dataset; --keep-far-field keeps all, and the
  // Glint layout keeps them unless asked.
  fs::create_directories(root() / "run");
  fs::copy_file(path("scene.ply"), root() / "run" / "scene.ply");
  std::ofstream(root() / "run" / "config.json") << R"({"dataset": ")" << path("D") << R"("})";
  EXPECT_EQ(runGlint("export " + path("run") + " -o " + path("run_near.ply")).status, 0);
  EXPECT_EQ(readPly(path("run_near.ply")).count, 3u);
  EXPECT_EQ(runGlint("export " + path("run") + " -o " + path("run_all.ply") + " --keep-far-field").status, 0);
  EXPECT_EQ(readPly(path("run_all.ply")).count, 6u);
  EXPECT_EQ(runGlint("export " + path("run") + " --format glint -o " + path("glint_all.ply")).status, 0);
  EXPECT_EQ(readPly(path("glint_all.ply")).count, 6u);
  EXPECT_EQ(runGlint("export " + path("run") + " --format glint --drop-far-field --far-field-radius 10 -o " +
                     path("glint_10.ply")).status, 0);
  EXPECT_EQ(readPly(path("glint_10.ply")).count, 4u);

  // --crop keeps the Gaussians whose centre lies in the box, and says how many went.
  const Vec3d c = cameras.centre;
  const double r = cameras.radius;
  char box[256];
  std::snprintf(box, sizeof(box), "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", c.x - 1, c.y - 1, c.z - 0.5 * r, c.x + 1, c.y + 1,
                c.z + 13 * r);
  Outcome cropped = runGlint("export " + path("scene.ply") + " -o " + path("crop.ply") + " --crop " + box);
  ASSERT_EQ(cropped.status, 0) << cropped.output;
  EXPECT_NE(cropped.output.find("dropped 1 Gaussians outside the --crop box"), std::string::npos) << cropped.output;
  EXPECT_EQ(readPly(path("crop.ply")).count, 5u);
  Outcome badBox = runGlint("export " + path("scene.ply") + " -o " + path("bad.ply") + " --crop 1,2,3");
  EXPECT_NE(badBox.status, 0);
  EXPECT_NE(badBox.output.find("--crop"), std::string::npos) << badBox.output;
}

// The INRIA 3DGS code's vertex properties, in its order (construct_list_of_attributes in
// its scene/gaussian_model.py): what its loader and every viewer built on it read.
std::vector<std::string> inriaProperties() {
  std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < 45; ++k) names.push_back("f_rest_" + std::to_string(k));
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    names.push_back(name);
  return names;
}

TEST_F(ExportCliTest, TheDefault3dgsExportIsInriasLayoutAndWarnsAboutUnbakedMirrors) {
  GaussianScene scene = sceneAt({{0, 0, 0}, {1, 0, 0}, {0, 2, 0}});
  scene.f0[1] = Rgb(0.95f);  // a mirror
  writeGaussianPly(path("scene.ply"), scene);
  Outcome run = runGlint("export " + path("scene.ply") + " -o " + path("inria.ply"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("warning: 1 of 3 Gaussians are reflective"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--bake-reflections"), std::string::npos) << run.output;
  // A loader written from the layout's documented property list, not Glint's reader: the
  // header, then 62 little-endian floats per vertex, read by position.
  std::ifstream in(path("inria.ply"), std::ios::binary);
  std::string line;
  std::vector<std::string> properties;
  size_t vertices = 0;
  std::getline(in, line);
  ASSERT_EQ(line, "ply");
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("format ", 0) == 0) {
      EXPECT_EQ(line, "format binary_little_endian 1.0");
    }
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    if (line.rfind("property ", 0) == 0) {
      EXPECT_EQ(line.rfind("property float ", 0), 0u) << line;
      properties.push_back(line.substr(line.rfind(' ') + 1));
    }
  }
  ASSERT_EQ(properties, inriaProperties());
  ASSERT_EQ(vertices, scene.size());
  std::vector<float> values(vertices * properties.size());
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
  ASSERT_TRUE(in.good());
  for (size_t i = 0; i < vertices; ++i) {
    const float* v = &values[i * properties.size()];
    EXPECT_EQ(v[0], scene.position[i].x);
    EXPECT_EQ(v[1], scene.position[i].y);
    EXPECT_EQ(v[54], scene.opacityLogit[i]);  // opacity, after the 45 f_rest
    for (int k = 9; k < 54; ++k) EXPECT_EQ(v[k], 0.0f) << "f_rest_" << k - 9;
  }
  // Baked, the reflections are in the colours and nothing needs saying.
  Outcome baked = runGlint("export " + path("scene.ply") + " -o " + path("baked.ply") +
                           " --bake-reflections --bake-directions 4");
  ASSERT_EQ(baked.status, 0) << baked.output;
  EXPECT_EQ(baked.output.find("are reflective"), std::string::npos) << baked.output;
}

// A 3DGS file as `splat-transform -H 0` writes it: the properties both layouts share. With
// `contradicting`, a header that says Glint's layout and a 3DGS-only f_rest_0 as well.
void writeCoreOnly3dgs(const fs::path& file, bool contradicting = false) {
  PlyTable table;
  table.add("x", {0.0f, 0.2f});
  table.add("y", {0.6f, 0.7f});
  table.add("z", {0.0f, 0.1f});
  for (const char* name : {"f_dc_0", "f_dc_1", "f_dc_2"}) table.add(name, {0.4f, -0.3f});
  table.add("opacity", {2.0f, 2.0f});
  for (const char* name : {"scale_0", "scale_1", "scale_2"}) table.add(name, {-2.0f, -2.5f});
  table.add("rot_0", {1.0f, 1.0f});
  for (const char* name : {"rot_1", "rot_2", "rot_3"}) table.add(name, {0.0f, 0.0f});
  PlyWriteOptions options;
  if (contradicting) {
    table.add("f_rest_0", {0.0f, 0.0f});
    options.comments = {"Glint Gaussian scene: f_dc_0..2 is linear diffuse colour (not SH)"};
  }
  writePly(file, table, options);
}

TEST_F(ExportCliTest, EveryCommandThatLoadsASceneTakesTheInputLayout) {
  for (const char* command : {"render", "view", "edit", "eval", "export"}) {
    Outcome help = runGlint(std::string(command) + " --help");
    EXPECT_NE(help.output.find("--input-layout"), std::string::npos) << command;
  }
  writeCoreOnly3dgs(path("h0.ply"));
  writeCoreOnly3dgs(path("contradicting.ply"), /*contradicting=*/true);
  std::ofstream(path("edits.json")) << R"({"glint_edits": 1, "operations": []})";
  // A file whose header says Glint's layout but holds 3DGS's f_rest: refused, naming the
  // file and the flag, by every command before other work.
  for (const std::string& args :
       {"edit " + path("contradicting.ply") + " " + path("edits.json") + " -o " + path("edited.ply"),
        "render " + path("contradicting.ply") + " -o " + path("frames") + " --dataset " + path("none"),
        "eval " + path("contradicting.ply") + " -o " + path("metrics.json") + " --dataset " + path("none"),
        "export " + path("contradicting.ply") + " -o " + path("out.ply")}) {
    Outcome run = runGlint(args);
    EXPECT_NE(run.status, 0) << args;
    EXPECT_NE(run.output.find("contradicting.ply"), std::string::npos) << args << "\n" << run.output;
    EXPECT_NE(run.output.find("--input-layout"), std::string::npos) << args << "\n" << run.output;
  }
  // A degree-0 splat file without Glint's header loads as 3DGS with the imported
  // materials, and says why.
  Outcome edit = runGlint("edit " + path("h0.ply") + " " + path("edits.json") + " -o " + path("edited.ply"));
  ASSERT_EQ(edit.status, 0) << edit.output;
  EXPECT_NE(edit.output.find("no Glint header or material properties, so read as a 3DGS file"), std::string::npos)
      << edit.output;
  EXPECT_NE(edit.output.find("materials set to a rough dielectric"), std::string::npos) << edit.output;
  GaussianScene edited = readGaussianPly(path("edited.ply"));
  ASSERT_EQ(edited.size(), 2u);
  EXPECT_EQ(edited.roughness[0], 0.9f);
  EXPECT_NEAR(tonemapFilmic(edited.diffuse[0].x), 0.5 + kShC0 * 0.4, 5e-5);
  // --input-layout glint still reads it as Glint's linear colour.
  Outcome asGlint = runGlint("edit " + path("h0.ply") + " " + path("edits.json") + " -o " + path("raw.ply") +
                             " --input-layout glint");
  ASSERT_EQ(asGlint.status, 0) << asGlint.output;
  EXPECT_EQ(readGaussianPly(path("raw.ply")).diffuse[0].x, 0.4f);
}

}  // namespace
}  // namespace glint
