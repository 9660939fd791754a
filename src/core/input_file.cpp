// Opening input files: regular files only, size limits, errors that name the file.
#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

namespace {

// What a non-regular file is, in the words of the error.
const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string sizeText(uint64_t bytes) {
  if (bytes >= (uint64_t(1) << 30)) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (uint64_t(1) << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// Throws for a stat of a file that is not a regular file of at most maxBytes.
void checkStat(const std::string& name, const struct stat& st, uint64_t maxBytes) {
  if (!S_ISREG(st.st_mode))
    throw Error(name, std::string("is ") + fileKind(st.st_mode) + ", not a regular file");
  if (uint64_t(st.st_size) > maxBytes)
    throw Error(name, "is " + std::to_string(uint64_t(st.st_size)) + " bytes, more than the " + sizeText(maxBytes) +
                          " this kind of file may hold (wrong file?)");
}

[[noreturn]] void throwOpenError(const std::string& name, int error) {
  if (error == ENOENT) throw Error(name, "file not found");
  if (error == ENAMETOOLONG) throw Error(name, "the name is too long for the file system");
  if (error == ENOTDIR) throw Error(name, "file not found (a part of the path is not a folder)");
  throw Error(name, std::string("cannot open for reading: ") + std::strerror(error));
}

}  // namespace

bool pathPresent(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::exists(std::filesystem::symlink_status(path, ec));
}

std::string quotedPath(const std::filesystem::path& path) { return printableText(path.string(), 200); }

uint64_t checkInputFile(const std::filesystem::path& path, uint64_t maxBytes) {
  const std::string name = quotedPath(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throwOpenError(name, errno);
  checkStat(name, st, maxBytes);
  return uint64_t(st.st_size);
}

std::string readInputFile(const std::filesystem::path& path, uint64_t maxBytes) {
  const std::string name = quotedPath(path);
  // O_NONBLOCK: opening a FIFO would otherwise wait for a writer forever.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throwOpenError(name, errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw Error(name, std::string("cannot read: ") + std::strerror(errno));
  checkStat(name, st, maxBytes);
  std::string contents(size_t(st.st_size), '\0');
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t got = ::read(fd, contents.data() + done, contents.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(name, std::string("cannot read: ") + std::strerror(errno));
    if (got == 0) break;  // the file shrank while being read: what is there is what it holds
    done += size_t(got);
  }
  contents.resize(done);
  return contents;
}

}  // namespace glint
