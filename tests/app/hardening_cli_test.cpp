// The hostile and careless inputs of issue 39 through the commands: FIFOs and devices in a
// capture, a device or a link as an export target, a second writer of a run folder, Glint's
// own small captures, and flag values quoted as given.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "app/run_glint.h"
#include "common/floor_capture.h"
#include "core/atomic_file.h"
#include "io/json_file.h"
#include "io/temp_folder.h"
#include "scene/nerf_synthetic_files.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

class HardeningCliTest : public ::testing::Test {
 protected:
  std::string at(const char* name) const { return (root_ / name).string(); }
  test::TempFolder folder_;
  const fs::path root_ = folder_.path();
};

// A FIFO or a device in place of a capture's files is one error naming the file, at once.
TEST_F(HardeningCliTest, FifosAndDevicesInACaptureAreRefusedWithoutHanging) {
  test::writeFloorCapture(root_ / "C");
  struct Case {
    const char* file;
    bool fifo;  // else a link to /dev/zero
    const char* detail;
  };
  for (const Case& c : {Case{"capture.json", true, "capture.json: is a FIFO"},
                        Case{"sparse/0/images.txt", true, "images.txt: is a FIFO"},
                        Case{"capture.json", false, "capture.json: is a device"},
                        Case{"sparse/0/cameras.txt", false, "cameras.txt: is a device"}}) {
    fs::remove_all(root_ / "D");
    fs::copy(root_ / "C", root_ / "D", fs::copy_options::recursive);
    const fs::path file = root_ / "D" / c.file;
    fs::remove(file);
    if (c.fifo)
      ASSERT_EQ(mkfifo(file.c_str(), 0644), 0);
    else
      fs::create_symlink("/dev/zero", file);
    const Outcome info = runGlint("info " + at("D"), /*timeoutSeconds=*/60);
    EXPECT_NE(info.status, 124) << c.file << ": timed out";
    EXPECT_NE(info.status, 0) << info.output;
    EXPECT_NE(info.output.find(c.detail), std::string::npos) << info.output;
  }
  // A folder at cameras.txt is reported as itself, not as a missing transforms file.
  fs::remove_all(root_ / "D");
  fs::copy(root_ / "C", root_ / "D", fs::copy_options::recursive);
  fs::remove(root_ / "D" / "sparse" / "0" / "cameras.txt");
  fs::create_directory(root_ / "D" / "sparse" / "0" / "cameras.txt");
  const Outcome info = runGlint("info " + at("D"));
  EXPECT_NE(info.output.find("cameras.txt: is a folder"), std::string::npos) << info.output;
  EXPECT_EQ(info.output.find("transforms_train.json"), std::string::npos) << info.output;
}

// Issue 39, item 7: Glint's own small capture, with its depth priors, trains.
TEST_F(HardeningCliTest, GlintsOwnSmallCaptureIsAccepted) {
  Outcome synth = runGlint("synth builtin:spheres -o " + at("CAP") +
                           " --layout capture --train 8 --res 64x48 --spp 8 --threads 2");
  ASSERT_EQ(synth.status, 0) << synth.output;
  const Outcome info = runGlint("info " + at("CAP"));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("problems: none"), std::string::npos) << info.output;
}

// Issue 39, items 4 and 6: outputs replace regular files only, and a run has one writer.
TEST_F(HardeningCliTest, ExportsReplaceRegularFilesOnlyAndARunHasOneWriter) {
  test::writeFloorCapture(root_ / "C");
  const Outcome train = runGlint("train " + at("C") + " -o " + at("RUN") + " --iters 4 --batch-rays 256 --threads 2");
  ASSERT_EQ(train.status, 0) << train.output;

  writeTextAtomically(root_ / "target.txt", "kept");
  fs::create_symlink(root_ / "target.txt", root_ / "link.ply");
  fs::create_symlink("/dev/null", root_ / "device.ply");
  for (const char* name : {"link.ply", "device.ply"}) {
    const Outcome out = runGlint("export " + at("RUN") + " --format 3dgs --force -o " + at(name));
    EXPECT_NE(out.status, 0) << out.output;
    EXPECT_NE(out.output.find("Glint replaces regular files only"), std::string::npos) << out.output;
    EXPECT_TRUE(fs::is_symlink(root_ / name));
  }
  EXPECT_EQ(readTextFile(root_ / "target.txt"), "kept");

  // A resumed run holds the folder; a second resume is refused with the holder's PID.
  const std::string resume = "train -o " + at("RUN") + " --resume --iters 400 --threads 1";
  fs::remove(root_ / "RUN" / ".glint-lock");  // the first train's, so that the wait below sees the resume's
  FILE* first = popen((std::string(GLINT_BINARY) + " " + resume + " > /dev/null 2>&1").c_str(), "r");
  ASSERT_NE(first, nullptr);
  bool locked = false;
  for (int i = 0; i < 200 && !locked; ++i) {  // until the first one holds the lock
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream lock(root_ / "RUN" / ".glint-lock");
    std::string line;
    locked = std::getline(lock, line) && line.find("glint train") != std::string::npos;
  }
  ASSERT_TRUE(locked);
  const Outcome second = runGlint(resume);
  pclose(first);
  EXPECT_NE(second.status, 0) << second.output;
  EXPECT_NE(second.output.find("is in use by pid"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("glint train"), std::string::npos) << second.output;
}

// Issue 39, item 9: one bad camera_angle_x in a NeRF-synthetic folder is one problem, not
// three (the layout was taken for the paper's, whose reader refused every file_path too).
TEST_F(HardeningCliTest, ABadFieldOfViewIsOneProblem) {
  test::writeNerfSyntheticDataset(root_ / "N", {{"train", 3}, {"test", 1}});
  nlohmann::json transforms = readJsonFile(root_ / "N" / "transforms_train.json");
  transforms["camera_angle_x"] = -1;
  writeTextAtomically(root_ / "N" / "transforms_train.json", transforms.dump());
  const Outcome info = runGlint("info " + at("N"));
  EXPECT_NE(info.status, 0);
  EXPECT_NE(info.output.find("problems: 1\n"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("camera_angle_x is -1"), std::string::npos) << info.output;
  EXPECT_EQ(info.output.find("render image"), std::string::npos) << info.output;

  // A 10 MB file_path is quoted cut, with its length (10,000,000 and the folder), not echoed whole.
  transforms["camera_angle_x"] = 0.69;
  transforms["frames"][0]["file_path"] = std::string(10000000, 'a');
  writeTextAtomically(root_ / "N" / "transforms_train.json", transforms.dump());
  const Outcome named = runGlint("info " + at("N"));
  EXPECT_NE(named.status, 0);
  EXPECT_NE(named.output.find("... (1000"), std::string::npos) << named.output.substr(0, 500);
  EXPECT_LT(named.output.size(), 2000u);
}

// Issue 39, item 9: a flag's limit is not quoted as a 309-digit number.
TEST_F(HardeningCliTest, PositiveFlagsQuoteTheValueGiven) {
  const Outcome out = runGlint("export " + at("none") + " --format 3dgs -o " + at("x.ply") + " --exposure -1");
  EXPECT_NE(out.status, 0);
  EXPECT_NE(out.output.find("--exposure: must be a finite number > 0, found -1"), std::string::npos) << out.output;
  EXPECT_LT(out.output.size(), 300u) << out.output;
}

}  // namespace
}  // namespace glint
