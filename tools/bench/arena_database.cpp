#include "rbsf/bench/arena_database.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace rbsf::bench {

std::string findBenchmarkStatistics() {
  if (const char* env = std::getenv("RBSF_OMPL_BENCHMARK_STATISTICS"); env && *env)
    return access(env, X_OK) == 0 ? env : "";
  std::vector<std::string> dirs;
  if (const char* path = std::getenv("PATH")) {
    std::istringstream in(path);
    for (std::string d; std::getline(in, d, ':');)
      if (!d.empty()) dirs.push_back(d);
  }
  dirs.push_back("/usr/bin");
  dirs.push_back("/usr/share/ompl/demos");
  for (const std::string& d : dirs) {
    const std::string p = d + "/ompl_benchmark_statistics";
    if (access(p.c_str(), X_OK) == 0) return p;
  }
  return {};
}

void makeArenaDatabase(const std::vector<std::string>& logs, const std::string& database) {
  const std::string script = findBenchmarkStatistics();
  if (script.empty())
    throw std::runtime_error(
        "ompl_benchmark_statistics not found (Debian package ompl-demos; "
        "scripts/install-deps.sh installs it); the .log files are written");
  const std::string tmp = database + ".tmp." + std::to_string(getpid());
  std::remove(tmp.c_str());
  std::vector<std::string> args = {script, "-d", tmp};
  args.insert(args.end(), logs.begin(), logs.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start ompl_benchmark_statistics");
  if (pid == 0) {
    // Its progress chatter goes nowhere; its errors stay on stderr.
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDOUT_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || access(tmp.c_str(), R_OK) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(script + " failed on the logs (exit status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  if (std::rename(tmp.c_str(), database.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(database + ": cannot write the database");
  }
}

}  // namespace rbsf::bench
