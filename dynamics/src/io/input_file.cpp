/// \file
/// \brief Input files (see input_file.h).

#include "rbsf/dynamics/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

std::string readInputFile(const std::string& path, const std::string& what, std::size_t max_bytes) {
  const std::string prefix = path + ": cannot read the " + what + ": ";
  // O_NONBLOCK: opening a FIFO with no writer must not hang before fstat says what it is.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(prefix + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st;
  if (::fstat(fd, &st) != 0) throw InputError(prefix + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw InputError(prefix + "it is a directory");
  if (!S_ISREG(st.st_mode)) throw InputError(prefix + "not a regular file");
  if (static_cast<std::size_t>(st.st_size) > max_bytes)
    throw InputError(prefix + std::to_string(st.st_size) + " bytes, more than the limit of " +
                     std::to_string(max_bytes));
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(prefix + std::strerror(errno));
    if (n == 0) break;  // the file shrank while read: what is there
    done += static_cast<std::size_t>(n);
  }
  text.resize(done);
  return text;
}

}  // namespace rbsf
