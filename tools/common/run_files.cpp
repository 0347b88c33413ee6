/// \file
/// \brief The files of one tool run (see run_files.h).

#include "rbsf/tools/run_files.h"

#include <sys/stat.h>

#include <climits>
#include <cstdlib>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"

namespace rbsf::tools {

RunFiles::Entry RunFiles::identify(const std::string& path, const std::string& option,
                                   bool follow) {
  Entry e;
  e.path = path;
  e.option = option;
  struct stat st;
  if ((follow ? ::stat(path.c_str(), &st) : ::lstat(path.c_str(), &st)) == 0) {
    e.exists = true;
    e.device = static_cast<unsigned long long>(st.st_dev);
    e.inode = static_cast<unsigned long long>(st.st_ino);
  }
  const std::string dir = directoryOf(path);
  const std::string name = path.substr(path.find_last_of('/') + 1);  // npos + 1 == 0
  char buf[PATH_MAX];
  e.resolved = (::realpath(dir.c_str(), buf) != nullptr ? std::string(buf) : dir) + "/" + name;
  return e;
}

bool RunFiles::same(const Entry& a, const Entry& b) {
  if (a.exists && b.exists) return a.device == b.device && a.inode == b.inode;
  return a.resolved == b.resolved;
}

void RunFiles::addInput(const std::string& path, const std::string& option) {
  if (!path.empty()) inputs_.push_back(identify(path, option, true));
}

void RunFiles::addOutput(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  checkWritable(path, option);  // a file name in a writable directory, not a special file
  Entry e = identify(path, option, false);
  for (const Entry& in : inputs_)
    if (same(e, in))
      throw InputError(option + ": '" + path + "' is the input given to " + in.option +
                       "; an output never replaces an input");
  for (const Entry& out : outputs_)
    if (same(e, out)) throw InputError(option + ": '" + path + "' is also given to " + out.option);
  outputs_.push_back(std::move(e));
}

}  // namespace rbsf::tools
