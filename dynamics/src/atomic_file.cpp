/// \file
/// \brief Atomic output files (see atomic_file.h).

#include "rbsf/dynamics/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "rbsf/dynamics/errors.h"

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
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(what + ": cannot move the output into place at '" + path + "'");
  }
}

void checkWritable(const std::string& path, const std::string& what) {
  const std::string::size_type slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "."
                          : slash == 0               ? "/"
                                                     : path.substr(0, slash);
  const std::string message = what + ": cannot write '" + path + "': ";
  struct stat st;
  if (path.empty() || path.back() == '/')
    throw InputError(what + ": '" + path + "' is not a file name");
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw InputError(message + "no directory '" + dir + "'");
  if (::access(dir.c_str(), W_OK) != 0) throw InputError(message + "directory not writable");
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw InputError(message + "it is a directory");
}

}  // namespace rbsf
