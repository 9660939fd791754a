// flock-based exclusive locks on run folders, shared within one process.
#include "core/folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <map>
#include <mutex>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable_text.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

struct HeldLock {
  int fd = -1;
  int users = 0;
};

// The locks this process holds, by folder: flock conflicts between two descriptors of one
// process too, so a second lock of a held folder shares the first one's descriptor.
std::mutex& heldMutex() {
  static std::mutex m;
  return m;
}
std::map<fs::path, HeldLock>& heldLocks() {
  static std::map<fs::path, HeldLock> locks;
  return locks;
}

fs::path canonicalFolder(const fs::path& folder) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  return ec ? fs::absolute(folder).lexically_normal() : canonical;
}

// What the holder wrote into the lock file ("pid 1234, glint train, since ..."), short.
std::string holderOf(int fd) {
  char text[256] = {};
  const ssize_t got = ::pread(fd, text, sizeof(text) - 1, 0);
  std::string holder = got > 0 ? std::string(text, size_t(got)) : std::string();
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\r')) holder.pop_back();
  return holder.empty() ? std::string("another process") : printableText(holder, 160);
}

std::string describeThisProcess(const std::string& holder) {
  char when[32] = "";
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  if (localtime_r(&now, &local)) std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S", &local);
  return "pid " + std::to_string(::getpid()) + ", " + holder + ", since " + when + "\n";
}

}  // namespace

FolderLock::FolderLock(const fs::path& folder, const std::string& holder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(quotedPath(folder), "cannot create folder: " + ec.message());
  folder_ = canonicalFolder(folder);
  std::lock_guard<std::mutex> guard(heldMutex());
  auto held = heldLocks().find(folder_);
  if (held != heldLocks().end()) {
    ++held->second.users;
    return;
  }
  const fs::path file = folder_ / kFolderLockName;
  // O_NOFOLLOW: a link planted in place of the lock file is not followed and written through.
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) throw Error(quotedPath(file), std::string("cannot open the folder's lock file: ") + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string by = holderOf(fd);
    ::close(fd);
    if (error == EWOULDBLOCK)
      throw Error(quotedPath(folder), "is in use by " + by + "; wait for it to finish or stop it first");
    throw Error(quotedPath(file), std::string("cannot lock: ") + std::strerror(error));
  }
  // Best effort: without its description the lock still holds, and a second writer is told
  // "another process".
  const std::string me = describeThisProcess(holder);
  if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, me.data(), me.size(), 0);
  heldLocks()[folder_] = HeldLock{fd, 1};
}

FolderLock::~FolderLock() {
  std::lock_guard<std::mutex> guard(heldMutex());
  auto held = heldLocks().find(folder_);
  if (held == heldLocks().end() || --held->second.users > 0) return;
  // The file stays: removing it would let a third process lock a new file while a second
  // still waits on the old one. flock is released by close.
  ::close(held->second.fd);
  heldLocks().erase(held);
}

bool isFolderLockFile(const fs::path& file) { return file.filename() == kFolderLockName; }

bool isEmptyButForLock(const fs::path& folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (!isFolderLockFile(it->path())) return false;
  return !ec;
}

}  // namespace glint
