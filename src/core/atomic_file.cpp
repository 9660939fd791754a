// Atomic writes by rename, and whole-file reads with clear errors.
#include "core/atomic_file.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// The characters of a machine's name in temporary file names: letters, digits and '-' (a '.'
// would end the stem, and a '_' parts of the name).
bool hostTagCharacter(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-'; }

// This machine's name as it goes into temporary file names, other characters as '-'.
const std::string& hostTag() {
  static const std::string tag = [] {
    char name[256] = "";
    if (gethostname(name, sizeof(name) - 1) != 0) return std::string("host");
    std::string t;
    for (const char* c = name; *c != '\0'; ++c)
      t += hostTagCharacter(*c) ? *c : '-';
    return t.empty() ? std::string("host") : t;
  }();
  return tag;
}

// Temporary files are named ".STEM.tmpPID_N_HOST.EXT": the real extension stays last because
// some writers pick the format from it, and the PID and the machine tell whose file it is
// (the ranks of an MPI job on several machines write into one shared folder).
std::string temporaryName(const fs::path& path, int counter) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) about "." + std::string&&.
  std::string name = ".";
  name += path.stem().string();
  name += ".tmp" + std::to_string(getpid()) + "_" + std::to_string(counter) + "_" + hostTag();
  name += path.extension().string();
  return name;
}

struct TemporaryOwner {
  pid_t pid = 0;
  std::string host;  // empty in the names of Glint before machines were named
};

// Whose temporary file a name is, or nothing when the name is not one of ours.
std::optional<TemporaryOwner> temporaryOwner(const std::string& name) {
  if (name.empty() || name[0] != '.') return std::nullopt;
  for (size_t at = name.find(".tmp", 1); at != std::string::npos; at = name.find(".tmp", at + 1)) {
    const char* first = name.data() + at + 4;
    const char* last = name.data() + name.size();
    pid_t pid = 0;
    auto [afterPid, pidError] = std::from_chars(first, last, pid);
    if (pidError != std::errc() || afterPid == first || pid <= 0 || afterPid == last || *afterPid != '_') continue;
    unsigned counter = 0;
    auto [afterCounter, counterError] = std::from_chars(afterPid + 1, last, counter);
    if (counterError != std::errc() || afterCounter == afterPid + 1) continue;
    if (afterCounter == last || *afterCounter == '.') return TemporaryOwner{pid, ""};
    if (*afterCounter != '_') continue;
    const char* host = afterCounter + 1;
    const char* hostEnd = host;
    while (hostEnd != last && hostTagCharacter(*hostEnd)) ++hostEnd;
    if (hostEnd != host && (hostEnd == last || *hostEnd == '.')) return TemporaryOwner{pid, std::string(host, hostEnd)};
  }
  return std::nullopt;
}

bool processIsGone(pid_t pid) { return kill(pid, 0) != 0 && errno == ESRCH; }

// Removes the temporaries that killed processes left in a folder (a checkpoint's can be
// hundreds of MB). A live process's, ours included, are kept: it may still rename them.
// Each folder is swept once per process, so writing many files into one folder stays linear.
void removeStaleTemporaries(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<fs::path> swept;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!swept.insert(folder.empty() ? fs::path(".") : folder).second) return;
  }
  std::error_code ec;
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    // Only this machine's processes can be asked whether they are gone.
    std::optional<TemporaryOwner> owner = temporaryOwner(it->path().filename().string());
    if (!owner || (!owner->host.empty() && owner->host != hostTag()) || !processIsGone(owner->pid)) continue;
    std::error_code ignored;
    if (it->is_regular_file(ignored)) fs::remove(it->path(), ignored);
  }
}

}  // namespace

void checkReplaceableOutput(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return;  // nothing there to lose
    throw Error(quotedPath(path), std::string("cannot be written: ") + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) return;
  const char* kind = S_ISLNK(st.st_mode)                        ? "a symbolic link"
                     : S_ISDIR(st.st_mode)                      ? "a folder"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                     : S_ISFIFO(st.st_mode)                     ? "a FIFO (named pipe)"
                                                                : "not a regular file";
  throw Error(quotedPath(path), std::string("is ") + kind +
                                    "; Glint replaces regular files only, even with --force: remove it or choose "
                                    "another name");
}

void writeAtomically(const fs::path& path, const std::function<void(const std::string&)>& write) {
  static std::atomic<int> counter{0};
  checkReplaceableOutput(path);
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.parent_path().string(), "cannot create folder: " + ec.message());
  }
  removeStaleTemporaries(path.parent_path());
  fs::path temp = path.parent_path() / temporaryName(path, counter.fetch_add(1));
  try {
    write(temp.string());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
  std::error_code renameError;
  fs::rename(temp, path, renameError);
  if (renameError) {
    std::error_code ignored;  // the rename's error is the one to report
    fs::remove(temp, ignored);
    throw Error(path.string(), "cannot move the finished file into place: " + renameError.message());
  }
}

void writeTextAtomically(const fs::path& path, const std::string& contents) {
  writeAtomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw Error(path.string(), std::string("cannot open for writing: ") + std::strerror(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) throw Error(path.string(), "write failed (disk full?)");
  });
}

std::string readTextFile(const fs::path& path) { return readInputFile(path, kMaxTextModelFileBytes); }

}  // namespace glint
