// Tests of the one way inputs are opened: regular files only (a FIFO never blocks), the size
// limit checked before reading, names quoted briefly, errors that name the file.
#include "core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/expect_error.h"
#include "core/activity.h"
#include "core/atomic_file.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::expectErrorNaming;

class InputFileTest : public ::testing::Test {
 protected:
  test::TempFolder folder_;
  const fs::path root_ = folder_.path();
};

TEST_F(InputFileTest, ReadsARegularFileWhole) {
  const fs::path file = root_ / "a.json";
  std::ofstream(file) << "{\"x\": 1}";
  EXPECT_EQ(readInputFile(file, 100), "{\"x\": 1}");
  EXPECT_EQ(checkInputFile(file), 8u);
}

// Issue 39: a FIFO in place of capture.json blocked `glint info` forever.
TEST_F(InputFileTest, AFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = root_ / "capture.json";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
  expectErrorNaming([&] { readInputFile(fifo, kMaxJsonFileBytes); }, fifo, {"FIFO", "not a regular file"});
  expectErrorNaming([&] { checkInputFile(fifo); }, fifo, {"FIFO"});
  expectErrorNaming([&] { readTextFile(fifo); }, fifo, {"FIFO"});
}

// Issue 39: a link to /dev/zero read for 30 s, then said "out of memory" naming no file.
TEST_F(InputFileTest, ADeviceAndAFolderAreRefusedAtOnce) {
  const fs::path device = root_ / "images.txt";
  fs::create_symlink("/dev/zero", device);
  expectErrorNaming([&] { readInputFile(device, kMaxTextModelFileBytes); }, device, {"is a device"});
  const fs::path folder = root_ / "cameras.txt";
  fs::create_directory(folder);
  expectErrorNaming([&] { readInputFile(folder, kMaxTextModelFileBytes); }, folder, {"is a folder"});
}

TEST_F(InputFileTest, TheSizeLimitIsCheckedBeforeReading) {
  const fs::path file = root_ / "big.json";
  std::ofstream(file) << std::string(1000, ' ');
  expectErrorNaming([&] { readInputFile(file, 999); }, file, {"1000 bytes", "more than the 999 bytes"});
  EXPECT_EQ(readInputFile(file, 1000).size(), 1000u);
}

TEST_F(InputFileTest, MissingFilesAndOverlongNamesAreNamed) {
  expectErrorNaming([&] { readInputFile(root_ / "none.json", 10); }, root_ / "none.json", {"file not found"});
  const fs::path longName = root_ / (std::string(300, 'a') + ".json");
  try {
    checkInputFile(longName);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("too long"), std::string::npos) << message;
    EXPECT_NE(message.find("bytes)"), std::string::npos) << message;  // cut, with its length
    EXPECT_LT(message.size(), 400u) << message;
  }
}

// The standard library's own file errors (a status() on a 10 MB name) are quoted briefly.
TEST_F(InputFileTest, FilesystemErrorsAreQuotedBriefly) {
  const std::string huge(1 << 20, 'b');
  std::error_code ec;
  try {
    (void)fs::is_regular_file(root_ / huge);
    ADD_FAILURE() << "no error";
  } catch (const fs::filesystem_error& e) {
    const std::string message = describeUnexpectedException(e);
    EXPECT_NE(message.find("the name is too long"), std::string::npos) << message;
    EXPECT_LT(message.size(), 400u);
  }
}

}  // namespace
}  // namespace glint
