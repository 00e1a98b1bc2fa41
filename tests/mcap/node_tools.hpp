#pragma once
// Runs the Node scripts of tests/mcap (which use @mcap/core from web/dashboard/node_modules) from the project root.
// Their exit status 77 means "skipped": node or the packages are missing, as for the browser test.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <sys/wait.h>

namespace fsd::mcap::test {

inline constexpr int kSkipped = 77;

inline bool node_available() { return std::system("command -v node >/dev/null 2>&1") == 0; }

// `node args`, its exit status and everything it printed (stdout and stderr).
inline int run_node(const std::string& args, std::string* out) {
  if (!node_available()) {
    *out = "node not found";
    return kSkipped;
  }
  FILE* p = popen(("node " + args + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  out->clear();
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out->append(buf, n);
  const int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace fsd::mcap::test
