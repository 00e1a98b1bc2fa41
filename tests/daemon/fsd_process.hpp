#pragma once
// The fsd binary run as a user runs it, for the daemon's end-to-end tests: exit status and everything it printed
// (stdout and stderr).
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <sys/wait.h>

namespace fsd::test {

// The binary: the environment's FSD_BINARY when set (a long sweep on a copy, while the tree is rebuilt), else the
// build's own (FSD_BINARY, compiled in).
inline std::string fsd_binary() {
  const char* env = std::getenv("FSD_BINARY");
  return env && *env ? std::string(env) : std::string(FSD_BINARY);
}

// Runs the fsd binary with `args` through the shell (after `shell_prefix`, e.g. a ulimit); returns its exit status,
// and its output in *out when given.
inline int run_fsd_with(const std::string& shell_prefix, const std::string& args, std::string* out = nullptr) {
  const std::string cmd = shell_prefix + " " + fsd_binary() + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  std::array<char, 4096> buf{};
  std::string text;
  while (std::fgets(buf.data(), buf.size(), p)) text += buf.data();
  const int rc = pclose(p);
  if (out) *out = std::move(text);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

inline int run_fsd(const std::string& args, std::string* out = nullptr) { return run_fsd_with("", args, out); }

}  // namespace fsd::test
