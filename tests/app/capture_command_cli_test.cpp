// glint capture end to end against a stand-in for COLMAP (a shell script that prints COLMAP's
// progress lines and writes prepared models): the largest model kept, undistortion when its
// cameras are distorted, priors kept or left out, failures that leave the output untouched,
// and the refusals. The real COLMAP runs in the colmap_capture CTest test.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/run_glint.h"
#include "io/colmap_model.h"

namespace {

namespace fs = std::filesystem;

using glint::ColmapCamera;
using glint::ColmapImage;
using glint::ColmapModel;
using glint::test::Outcome;
using glint::test::runGlint;

// Reads the options COLMAP's tools take, logs each call, fails when asked, and otherwise
// prints what COLMAP 3.8 prints and writes the models prepared in $FAKE_COLMAP.
constexpr const char* kFakeColmap = R"sh(#!/bin/sh
tool="$1"; shift
echo "$tool $*" >> "$FAKE_COLMAP/calls.txt"
[ "$QT_QPA_PLATFORM" = offscreen ] || { echo "QT_QPA_PLATFORM is not offscreen"; exit 9; }
while [ $# -gt 0 ]; do
  case "$1" in
    --database_path) db="$2" ;; --image_path) images="$2" ;; --output_path) out="$2" ;;
    --input_path) input="$2" ;; --path) model="$2" ;;
  esac
  shift
done
if [ "$FAKE_COLMAP_FAIL" = "$tool" ]; then echo "working on it"; echo "F1128 check failed in $tool" >&2; exit 3; fi
case "$tool" in
  feature_extractor)
    n=$(ls "$images" | wc -l); i=1
    while [ $i -le $n ]; do echo "Processed file [$i/$n]"; i=$((i + 1)); done
    : > "$db" ;;
  exhaustive_matcher|sequential_matcher) echo "Matching block [1/1, 1/1] in 0.100s" ;;
  mapper) [ -d "$FAKE_COLMAP/models" ] && cp -R "$FAKE_COLMAP/models/." "$out/"; echo "Registering image #3 (3)" ;;
  image_undistorter)
    mkdir -p "$out/images" "$out/sparse" "$out/stereo"
    for f in "$images"/*; do echo undistorted > "$out/images/$(basename "$f")"; done
    cp "$FAKE_COLMAP/undistorted/"* "$out/sparse/" ;;
  model_analyzer) printf 'Registered images: 3\nPoints: 2\nMean track length: 2.5\nMean reprojection error: 0.75px\n' ;;
  *) echo "unknown tool $tool"; exit 2 ;;
esac
)sh";

ColmapModel model(const std::string& cameraModel, std::vector<double> params, int width,
                  const std::vector<std::string>& names) {
  ColmapModel m;
  m.cameras.push_back(ColmapCamera{1, cameraModel, width, 20, std::move(params)});
  uint32_t id = 1;
  for (const std::string& name : names) {
    ColmapImage image;
    image.id = id++;
    image.qvec = glint::Quatd{1, 0, 0, 0};
    image.tvec = glint::Vec3d{0, 0, double(id)};
    image.cameraId = 1;
    image.name = name;
    m.images.push_back(image);
  }
  for (uint64_t i = 1; i <= 2; ++i) {
    glint::ColmapPoint point;
    point.id = i;
    point.xyz = glint::Vec3d{0, 0, double(i)};
    point.error = 0.5;
    m.points.push_back(point);
  }
  return m;
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class CaptureCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_capture_command_test_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "fake");
    std::ofstream(root_ / "fake" / "colmap") << kFakeColmap;
    fs::permissions(root_ / "fake" / "colmap", fs::perms::owner_all);
    // The photographs of a capture (images/, priors/, capture.json), as glint synth writes one.
    fs::create_directories(root_ / "photos" / "images");
    for (const char* name : {"a.png", "b.png", "c.png", "d.png"}) std::ofstream(root_ / "photos" / "images" / name) << name;
    fs::create_directories(root_ / "photos" / "priors" / "normal");
    std::ofstream(root_ / "photos" / "priors" / "normal" / "a.png") << "normal";
    std::ofstream(root_ / "photos" / "capture.json") << "{\"photo_transfer\": \"filmic\"}\n";
    // COLMAP's models: sparse/0 registers two photographs, sparse/1 three (the one to keep).
    prepareModels("PINHOLE", {30, 30, 20, 10});
  }
  void TearDown() override { fs::remove_all(root_); }

  void prepareModels(const std::string& cameraModel, std::vector<double> params) {
    fs::remove_all(root_ / "fake" / "models");
    glint::writeColmapModelBinary(root_ / "fake" / "models" / "0", model("PINHOLE", {30, 30, 20, 10}, 40, {"a.png", "b.png"}));
    glint::writeColmapModelBinary(root_ / "fake" / "models" / "1",
                                  model(cameraModel, std::move(params), 40, {"a.png", "b.png", "c.png"}));
    glint::writeColmapModelBinary(root_ / "fake" / "undistorted",
                                  model("PINHOLE", {30, 30, 21, 10}, 42, {"a.png", "b.png", "c.png"}));
  }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  // glint capture with the stand-in COLMAP; `environment` adds shell assignments.
  Outcome captureWith(const std::string& environment, const std::string& flags) const {
    return runGlint("capture " + flags + " --colmap " + path("fake/colmap"), 0,
                    "FAKE_COLMAP=" + path("fake") + " " + environment);
  }
  fs::path root_;
};

TEST_F(CaptureCommandTest, KeepsTheLargestModelWithThePhotographsAndPriors) {
  Outcome run = captureWith("", path("photos") + " -o " + path("out"));
  ASSERT_EQ(run.status, 0) << run.output;
  fs::path out = root_ / "out";
  ColmapModel kept = glint::readColmapModel(out / "sparse" / "0");
  EXPECT_EQ(kept.images.size(), 3u);  // sparse/1, not sparse/0
  EXPECT_EQ(kept.format, glint::ColmapFormat::Binary);
  for (const char* name : {"a.png", "b.png", "c.png", "d.png"}) EXPECT_EQ(fileText(out / "images" / name), name);
  EXPECT_EQ(fileText(out / "priors" / "normal" / "a.png"), "normal");
  EXPECT_EQ(fileText(out / "capture.json"), "{\"photo_transfer\": \"filmic\"}\n");
  EXPECT_TRUE(fs::exists(out / "colmap" / "database.db"));
  EXPECT_NE(fileText(out / "colmap" / "log.txt").find("Processed file [4/4]"), std::string::npos);
  EXPECT_FALSE(fs::exists(root_ / ".out.glint-capture-partial"));
  // With priors the camera is a pinhole with square pixels, so the priors stay aligned with
  // the photographs and fy cannot drift from fx.
  std::string calls = fileText(root_ / "fake" / "calls.txt");
  EXPECT_NE(calls.find("--ImageReader.camera_model SIMPLE_PINHOLE"), std::string::npos) << calls;
  EXPECT_EQ(calls.find("image_undistorter"), std::string::npos) << calls;
  EXPECT_NE(calls.find("--SiftExtraction.use_gpu 0"), std::string::npos) << calls;
  // What it registered, the reprojection error, what was left out and what to run next.
  EXPECT_NE(run.output.find("registered 3 of 4 photographs (2 models made, the largest kept): 2 points, mean track "
                            "length 2.50, mean reprojection error 0.75 px"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("1 photograph(s) have no camera and are left out of training: d.png"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("glint train " + out.string() + " -o " + out.string() + "-run"), std::string::npos)
      << run.output;
  // Glint opens what it wrote.
  Outcome info = runGlint("info " + out.string());
  EXPECT_NE(info.output.find("COLMAP binary model sparse/0, 3 images"), std::string::npos) << info.output;
}

TEST_F(CaptureCommandTest, UndistortsADistortedModelAndLeavesThePriorsOut) {
  prepareModels("OPENCV", {30, 30, 20, 10, -0.05, 0.001, 0, 0});
  Outcome run = captureWith("", path("photos") + " -o " + path("out") + " --camera-model OPENCV");
  ASSERT_EQ(run.status, 0) << run.output;
  fs::path out = root_ / "out";
  ColmapModel kept = glint::readColmapModel(out / "sparse" / "0");
  EXPECT_EQ(kept.cameras.at(0).width, 42);  // image_undistorter's model
  EXPECT_EQ(fileText(out / "images" / "a.png"), "undistorted\n");
  EXPECT_FALSE(fs::exists(out / "priors"));
  EXPECT_FALSE(fs::exists(out / "colmap" / "undistorted"));
  EXPECT_NE(run.output.find("priors/ left out"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("cameras: OPENCV, undistorted to pinholes"), std::string::npos) << run.output;
}

TEST_F(CaptureCommandTest, PhotographsAloneGetTheOpenCvModelAndKnownIntrinsicsStartIt) {
  fs::create_directories(root_ / "loose");
  for (const char* name : {"a.JPG", "b.jpg", "c.jpeg", "d.png"}) std::ofstream(root_ / "loose" / name) << name;
  std::ofstream(root_ / "loose" / "notes.txt") << "not a photograph";
  prepareModels("OPENCV", {30, 30, 20, 10, -0.05, 0, 0, 0});
  Outcome run = captureWith("", path("loose") + " -o " + path("out") + " --threads 1 --matcher sequential");
  ASSERT_EQ(run.status, 0) << run.output;
  std::string calls = fileText(root_ / "fake" / "calls.txt");
  EXPECT_NE(calls.find("--ImageReader.camera_model OPENCV"), std::string::npos) << calls;
  EXPECT_NE(calls.find("sequential_matcher"), std::string::npos) << calls;
  EXPECT_NE(calls.find("--SiftExtraction.num_threads 1"), std::string::npos) << calls;
  EXPECT_NE(calls.find("image_undistorter"), std::string::npos) << calls;
  EXPECT_EQ(calls.find("camera_params"), std::string::npos) << calls;
  EXPECT_FALSE(fs::exists(root_ / "out" / "colmap" / "images" / "notes.txt"));
  EXPECT_NE(run.output.find("4 photographs in " + path("loose")), std::string::npos) << run.output;

  // A capture's own pinhole camera starts the estimate unless --no-intrinsics: square pixels
  // as one focal length, others with both (and then a PINHOLE camera).
  glint::writeColmapModelBinary(root_ / "photos" / "sparse" / "0", model("PINHOLE", {31, 31, 20, 10}, 40, {"a.png"}));
  fs::remove(root_ / "fake" / "calls.txt");
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out2")).status, 0);
  calls = fileText(root_ / "fake" / "calls.txt");
  EXPECT_NE(calls.find("--ImageReader.camera_model SIMPLE_PINHOLE"), std::string::npos) << calls;
  EXPECT_NE(calls.find("--ImageReader.camera_params 31,20,10"), std::string::npos) << calls;
  glint::writeColmapModelBinary(root_ / "photos" / "sparse" / "0", model("PINHOLE", {31, 32, 20, 10}, 40, {"a.png"}));
  fs::remove(root_ / "fake" / "calls.txt");
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out4")).status, 0);
  calls = fileText(root_ / "fake" / "calls.txt");
  EXPECT_NE(calls.find("--ImageReader.camera_model PINHOLE"), std::string::npos) << calls;
  EXPECT_NE(calls.find("--ImageReader.camera_params 31,32,20,10"), std::string::npos) << calls;
  fs::remove(root_ / "fake" / "calls.txt");
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out3") + " --no-intrinsics").status, 0);
  EXPECT_EQ(fileText(root_ / "fake" / "calls.txt").find("camera_params"), std::string::npos);
}

TEST_F(CaptureCommandTest, AFailedStepLeavesTheOutputAsItWasAndKeepsTheLog) {
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out")).status, 0);
  std::string before = fileText(root_ / "out" / "colmap" / "log.txt");
  Outcome run = captureWith("FAKE_COLMAP_FAIL=mapper", path("photos") + " -o " + path("out") + " --force");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("| F1128 check failed in mapper"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("colmap mapper: exited with status 3"), std::string::npos) << run.output;
  fs::path work = root_ / ".out.glint-capture-partial";
  EXPECT_NE(run.output.find((work / "colmap" / "log.txt").string()), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(work / "colmap" / "log.txt"));
  EXPECT_EQ(fileText(root_ / "out" / "colmap" / "log.txt"), before);  // the earlier capture is intact
  // The next run clears the kept work folder and succeeds.
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out") + " --force").status, 0);
  EXPECT_FALSE(fs::exists(work));
}

TEST_F(CaptureCommandTest, NoModelIsOneClearError) {
  fs::remove_all(root_ / "fake" / "models");
  Outcome run = captureWith("", path("photos") + " -o " + path("out"));
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("colmap mapper: registered no photographs"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(root_ / "out"));
}

TEST_F(CaptureCommandTest, RefusesWhatItMustNotTouch) {
  // Without COLMAP: how to install it.
  Outcome run = runGlint("capture " + path("photos") + " -o " + path("out") + " --colmap glint-no-such-colmap");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("COLMAP is not installed: install Debian's with `apt-get install colmap`"),
            std::string::npos)
      << run.output;
  // An output the user made, with or without --force.
  fs::create_directories(root_ / "mine");
  std::ofstream(root_ / "mine" / "thesis.tex") << "mine";
  for (const char* force : {"", " --force"}) {
    run = captureWith("", path("photos") + " -o " + path("mine") + force);
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("was not written by glint capture"), std::string::npos) << run.output;
    EXPECT_EQ(fileText(root_ / "mine" / "thesis.tex"), "mine");
  }
  // An earlier capture needs --force.
  ASSERT_EQ(captureWith("", path("photos") + " -o " + path("out")).status, 0);
  run = captureWith("", path("photos") + " -o " + path("out"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("already holds a capture; pass --force to replace it"), std::string::npos) << run.output;
  // The output inside the photographs, no photographs, too few, an unknown camera model.
  run = captureWith("", path("photos") + " -o " + path("photos/capture"));
  EXPECT_NE(run.output.find("is inside the photographs' folder"), std::string::npos) << run.output;
  fs::create_directories(root_ / "empty");
  run = captureWith("", path("empty") + " -o " + path("out4"));
  EXPECT_NE(run.output.find("holds no photographs: no JPEG or PNG file in it or in its images/ folder"),
            std::string::npos)
      << run.output;
  fs::create_directories(root_ / "two");
  for (const char* name : {"a.jpg", "b.jpg"}) std::ofstream(root_ / "two" / name) << name;
  run = captureWith("", path("two") + " -o " + path("out4"));
  EXPECT_NE(run.output.find("holds 2 photograph(s); structure from motion needs at least 3"), std::string::npos)
      << run.output;
  run = captureWith("", path("photos") + " -o " + path("out4") + " --camera-model FISHY");
  EXPECT_NE(run.output.find("--camera-model FISHY: not a COLMAP camera model"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(root_ / "out4"));
}

TEST_F(CaptureCommandTest, TrainOnPhotographsPointsToCapture) {
  Outcome run = runGlint("train " + path("photos") + " -o " + path("run") + " --iters 1");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("holds photographs but no cameras; get them with COLMAP: glint capture"),
            std::string::npos)
      << run.output;
}

}  // namespace
