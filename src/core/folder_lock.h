// An exclusive lock on a folder that one process writes (a training run), so that a second
// writer is refused with the name of the process that holds it.
#pragma once

#include <filesystem>
#include <string>

namespace glint {

// The lock file inside a locked folder. Folder checks that look for an empty or unfinished
// run ignore it.
inline constexpr const char* kFolderLockName = ".glint-lock";

// Holds flock(2) on FOLDER/.glint-lock from construction to destruction. The kernel drops the
// lock when the process ends however it ends (a SIGKILL included), so a stale lock file
// never blocks anyone. Within one process the lock is shared: a second FolderLock on the same
// folder (a viewer inside `glint train`) succeeds.
class FolderLock {
 public:
  // Creates the folder if needed and takes its lock for `holder` (e.g. "glint train"), or
  // throws Error naming the folder and the process that holds it (its PID, command and start
  // time, as it wrote them into the lock file).
  FolderLock(const std::filesystem::path& folder, const std::string& holder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
};

// True when `name` is the file name of the lock (kFolderLockName).
bool isFolderLockFile(const std::filesystem::path& file);

// True when the folder holds nothing but, perhaps, its lock file.
bool isEmptyButForLock(const std::filesystem::path& folder);

}  // namespace glint
