// Tests of run-folder locks: a second process is refused with the holder's PID, the lock
// is shared within one process, and a dead holder's lock file blocks nobody.
#include "core/folder_lock.h"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "common/locking_child.h"
#include "core/error.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

class FolderLockTest : public ::testing::Test {
 protected:
  test::TempFolder folder_;
  const fs::path root_ = folder_ / "run";  // made by the first lock
};

// A child holding the folder's lock as `glint train` does (left held: the child exits later).
test::LockingChild lockInChild(const fs::path& folder) {
  return test::holdLockInChild([&] { return new FolderLock(folder, "glint train") != nullptr; });
}

TEST_F(FolderLockTest, ASecondProcessIsRefusedWithTheHoldersPid) {
  const test::LockingChild child = lockInChild(root_);
  try {
    FolderLock second(root_, "glint view");
    ADD_FAILURE() << "the second writer was let in";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("is in use by pid " + std::to_string(child.pid)), std::string::npos) << message;
    EXPECT_NE(message.find("glint train"), std::string::npos) << message;
  }
  test::finish(child);
  // The holder is gone (its lock with it); its lock file stays and blocks nobody.
  EXPECT_TRUE(fs::exists(root_ / kFolderLockName));
  EXPECT_NO_THROW(FolderLock(root_, "glint train"));
}

TEST_F(FolderLockTest, TheLockIsSharedWithinAProcess) {
  std::optional<FolderLock> trainer;
  trainer.emplace(root_, "glint train");
  { FolderLock viewer(root_ / ".", "glint view"); }  // the same folder, another spelling
  // Still held after the inner lock is gone: another open of the lock file cannot take it.
  // (A forked child inherits this process's lock; another program opens the file anew.)
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open((root_ / kFolderLockName).c_str(), O_RDWR);
    _exit(fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) != 0 ? 7 : 0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_EQ(WEXITSTATUS(status), 7);
}

TEST_F(FolderLockTest, EmptyButForTheLock) {
  fs::create_directories(root_);
  EXPECT_TRUE(isEmptyButForLock(root_));
  { FolderLock lock(root_, "glint train"); }
  EXPECT_TRUE(isEmptyButForLock(root_));
  std::ofstream(root_ / "config.json") << "{}";
  EXPECT_FALSE(isEmptyButForLock(root_));
  EXPECT_TRUE(isFolderLockFile(root_ / kFolderLockName));
  EXPECT_FALSE(isFolderLockFile(root_ / "config.json"));
}

}  // namespace
}  // namespace glint
