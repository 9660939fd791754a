// Tests of atomic file writes: folders created, contents replaced, no temporary files left
// behind, the original kept when the writer fails, and clear errors for missing files.
#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards, so tests never see each other's files.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() /
            ("glint_atomic_file_" + std::to_string(getpid()) + "_" + std::string(info->name()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }

  // Every regular file under the root, so stray temporaries are noticed wherever they are.
  std::vector<fs::path> allFiles() const {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root_))
      if (entry.is_regular_file()) files.push_back(entry.path());
    return files;
  }

  fs::path root_;
};

TEST_F(AtomicFileTest, CreatesParentFolders) {
  fs::path path = root_ / "a" / "b" / "c" / "file.txt";
  writeTextAtomically(path, "hello");
  ASSERT_TRUE(fs::exists(path));
  EXPECT_EQ(readTextFile(path), "hello");
  EXPECT_EQ(allFiles(), std::vector<fs::path>{path});
}

TEST_F(AtomicFileTest, ReplacesExistingContents) {
  fs::path path = root_ / "file.json";
  writeTextAtomically(path, "a much longer first version of the file");
  writeTextAtomically(path, "short");
  EXPECT_EQ(readTextFile(path), "short");
  EXPECT_EQ(allFiles(), std::vector<fs::path>{path});
}

TEST_F(AtomicFileTest, KeepsBinaryBytesExactly) {
  fs::path path = root_ / "bytes.bin";
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes.push_back(char(i));
  bytes.append("\r\n\n\0end", 7);  // embedded NUL and line endings survive
  writeTextAtomically(path, bytes);
  EXPECT_EQ(readTextFile(path), bytes);
}

TEST_F(AtomicFileTest, EmptyContentsMakeAnEmptyFile) {
  fs::path path = root_ / "empty.txt";
  writeTextAtomically(path, "");
  ASSERT_TRUE(fs::exists(path));
  EXPECT_EQ(fs::file_size(path), 0u);
  EXPECT_EQ(readTextFile(path), "");
}

TEST_F(AtomicFileTest, WriterReceivesATemporaryPathInTheSameFolderWithTheSameExtension) {
  fs::path path = root_ / "sub" / "image.exr";
  std::string seenTemp;
  writeAtomically(path, [&](const std::string& temp) {
    seenTemp = temp;
    std::ofstream(temp) << "data";
  });
  EXPECT_NE(fs::path(seenTemp), path);
  EXPECT_EQ(fs::path(seenTemp).parent_path(), path.parent_path());  // same folder: rename cannot cross devices
  EXPECT_EQ(fs::path(seenTemp).extension(), ".exr");                // writers pick the format from it
  EXPECT_FALSE(fs::exists(seenTemp));
  EXPECT_EQ(readTextFile(path), "data");
}

TEST_F(AtomicFileTest, ThrowingWriterLeavesOriginalUntouchedAndNoTemporary) {
  fs::path path = root_ / "keep.txt";
  writeTextAtomically(path, "original");
  std::string seenTemp;
  EXPECT_THROW(writeAtomically(path,
                               [&](const std::string& temp) {
                                 seenTemp = temp;
                                 std::ofstream(temp) << "half-written";  // the failure comes after some output
                                 throw std::runtime_error("writer failed");
                               }),
               std::runtime_error);
  EXPECT_FALSE(seenTemp.empty());
  EXPECT_FALSE(fs::exists(seenTemp));
  EXPECT_EQ(readTextFile(path), "original");
  EXPECT_EQ(allFiles(), std::vector<fs::path>{path});
}

TEST_F(AtomicFileTest, ThrowingWriterDoesNotCreateTheTarget) {
  fs::path path = root_ / "never.txt";
  EXPECT_THROW(writeAtomically(path, [](const std::string&) { throw Error("x", "no"); }), Error);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(allFiles().empty());
}

TEST_F(AtomicFileTest, ReadingAMissingFileThrowsErrorNamingIt) {
  fs::path path = root_ / "does_not_exist.txt";
  try {
    readTextFile(path);
    FAIL() << "expected glint::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicFileTest, WritingWhereAFileBlocksTheFolderThrowsError) {
  // A regular file where a parent folder should be: the folder cannot be created.
  writeTextAtomically(root_ / "blocker", "x");
  fs::path path = root_ / "blocker" / "child.txt";
  EXPECT_THROW(writeTextAtomically(path, "y"), Error);
  EXPECT_EQ(readTextFile(root_ / "blocker"), "x");
}

TEST_F(AtomicFileTest, AFolderWhereTheFileShouldGoIsRefusedBeforeWriting) {
  fs::create_directories(root_ / "taken" / "inside");
  try {
    writeTextAtomically(root_ / "taken", "x");
    FAIL() << "expected Error";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("is a folder; Glint replaces regular files only"), std::string::npos) << message;
  }
  EXPECT_TRUE(fs::is_directory(root_ / "taken" / "inside"));
  EXPECT_EQ(allFiles().size(), 0u);
}

// Issue 39: `export --force` onto /dev/full replaced the device with a regular file. Only
// regular files are replaced; a link is not replaced either (nor what it points to).
TEST_F(AtomicFileTest, DevicesLinksAndFifosAreNeverReplaced) {
  fs::create_symlink("/dev/null", root_ / "device.ply");
  std::ofstream(root_ / "target.txt") << "kept";
  fs::create_symlink(root_ / "target.txt", root_ / "link.ply");
  ASSERT_EQ(mkfifo((root_ / "fifo.ply").c_str(), 0644), 0);
  for (const char* name : {"device.ply", "link.ply", "fifo.ply"}) {
    EXPECT_THROW(writeTextAtomically(root_ / name, "x"), Error) << name;
    EXPECT_TRUE(fs::is_symlink(root_ / name) || fs::is_fifo(root_ / name)) << name;
  }
  EXPECT_EQ(readTextFile(root_ / "target.txt"), "kept");
  try {
    checkReplaceableOutput("/dev/full");
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a device"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(checkReplaceableOutput(root_ / "target.txt"));
  EXPECT_NO_THROW(checkReplaceableOutput(root_ / "absent.ply"));
}

// The PID of a child that has exited and been reaped: no process has it (until reused).
pid_t deadPid() {
  pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

TEST_F(AtomicFileTest, RemovesTemporariesOfDeadProcessesAndKeepsLiveOnes) {
  fs::path folder = root_ / "run";
  fs::create_directories(folder);
  const pid_t dead = deadPid();
  const fs::path stale = folder / (".state.tmp" + std::to_string(dead) + "_3.bin");
  const fs::path staleNoExtension = folder / (".log.tmp" + std::to_string(dead) + "_0");
  const fs::path live = folder / (".state.tmp" + std::to_string(getpid()) + "_99.bin");
  const fs::path notOurs = folder / ".state.tmpfoo_1.bin";  // not a PID: left alone
  char host[256] = "";
  gethostname(host, sizeof(host) - 1);
  std::string here;
  for (const char* c = host; *c != '\0'; ++c) here += std::isalnum((unsigned char)*c) || *c == '-' ? *c : '-';
  // Named with this machine: its process is gone, so removed. Named with another machine (an
  // MPI rank elsewhere writing into a shared folder): whether its PID lives cannot be told
  // from here, so kept.
  const fs::path staleHere = folder / (".state.tmp" + std::to_string(dead) + "_4_" + here + ".bin");
  const fs::path elsewhere = folder / (".state.tmp" + std::to_string(dead) + "_5_other-node-7.bin");
  for (const fs::path& p : {stale, staleNoExtension, live, notOurs, staleHere, elsewhere}) std::ofstream(p) << "partial";
  writeTextAtomically(folder / "state.bin", "complete");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(staleNoExtension));
  EXPECT_FALSE(fs::exists(staleHere));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(notOurs));
  EXPECT_TRUE(fs::exists(elsewhere));
  EXPECT_EQ(readTextFile(folder / "state.bin"), "complete");
}

}  // namespace
}  // namespace glint
