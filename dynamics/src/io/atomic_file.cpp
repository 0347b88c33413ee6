/// \file
/// \brief Atomic output files (see atomic_file.h).

#include "rbsf/dynamics/io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

std::string temporaryPathFor(const std::string& path) {
  return path + ".tmp." + std::to_string(::getpid());
}

void writeFileAtomically(const std::string& path, std::string_view text, const std::string& what) {
  const std::string tmp = temporaryPathFor(path);
  const std::string message = what + ": cannot write '" + path + "'";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(message);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw InputError(message);
    }
  }
  moveIntoPlace(tmp, path, what);
}

namespace {

/// True when `path` exists and is not a regular file (lstat: a symbolic link counts).
bool specialFile(const std::string& path, bool& directory) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) return false;
  directory = S_ISDIR(st.st_mode);
  return !S_ISREG(st.st_mode);
}

}  // namespace

void moveIntoPlace(const std::string& tmp, const std::string& path, const std::string& what) {
  bool directory = false;
  if (specialFile(path, directory)) {  // rename would replace the device, FIFO or link itself
    std::remove(tmp.c_str());
    throw InputError(what + ": cannot write '" + path + "': it exists and is not a regular file");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(what + ": cannot move the output into place at '" + path + "'");
  }
}

std::string directoryOf(const std::string& path) {
  const std::string::size_type slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

void checkWritable(const std::string& path, const std::string& what) {
  const std::string dir = directoryOf(path);
  const std::string message = what + ": cannot write '" + path + "': ";
  struct stat st;
  if (path.empty() || path.back() == '/')
    throw InputError(what + ": '" + path + "' is not a file name");
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw InputError(message + "no directory '" + dir + "'");
  bool directory = false;
  if (specialFile(path, directory))
    throw InputError(message + (directory ? "it is a directory"
                                          : "it exists and is not a regular file (a device, "
                                            "FIFO or symbolic link is never replaced)"));
  // The directory takes a new file: the real test (permissions, read-only or special file
  // systems such as /proc), made before any work instead of after it.
  std::string probe = dir + "/.rbsf-write-check-XXXXXX";
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw InputError(message + "cannot create a file in '" + dir + "' (" + std::strerror(errno) +
                     ")");
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace rbsf
