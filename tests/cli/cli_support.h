#pragma once
/// \file
/// \brief What the command-line tests share: running a tool and reading its outputs.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace rbsf::cli_test {

/// \brief Exit status (-1 when killed by a signal) and the captured streams of a run.
struct Result {
  int status = -1;
  std::string out, err;
};

/// \brief The whole file (empty when missing).
inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

/// \brief Run a shell command line, capturing stdout and stderr separately.
inline Result run(const std::string& args) {
  static int counter = 0;
  const std::string base = ::testing::TempDir() + "rbsf_cli_" + std::to_string(getpid()) + "_" +
                           std::to_string(counter++);
  const std::string cmd = args + " >" + base + ".out 2>" + base + ".err";
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  return r;
}

/// \brief A file in the test temporary directory holding `text`.
inline std::string writeTemp(const std::string& name, const std::string& text) {
  // ctest runs each case in its own process, in parallel: names carry the pid.
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_" + name;
  std::ofstream(path) << text;
  return path;
}

/// \brief How a run stopped by a signal ended: its pid and exit status (-1 when the signal
///        killed it instead of the tool exiting).
struct Stopped {
  pid_t pid = -1;
  int status = -1;
};

/// \brief Start `argv` (stdout and stderr to /dev/null), send it `signal` after `delay`, and
///        wait for it.
inline Stopped runAndSignal(const std::vector<std::string>& argv, int signal,
                            std::chrono::milliseconds delay) {
  Stopped s;
  s.pid = fork();
  if (s.pid < 0) return s;
  if (s.pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(99);
  }
  std::this_thread::sleep_for(delay);
  kill(s.pid, signal);
  int raw = 0;
  if (waitpid(s.pid, &raw, 0) == s.pid && WIFEXITED(raw)) s.status = WEXITSTATUS(raw);
  return s;
}

}  // namespace rbsf::cli_test
