#pragma once
// Where tests write their temporary files: a directory of this test process's own under ::testing::TempDir(),
// removed with everything in it when the process exits. ctest -j runs each test in its own process, all sharing
// TempDir(), so names must not collide across processes; and a run must leave nothing behind. Set
// FSD_KEEP_TEST_FILES in the environment to keep the directory for looking at a failure.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace fsd::test {

// TempDir()/fsd_test_<pid>, created on first use. A fork()ed child that leaves with _exit() or exec() does not
// remove it; only the process that created it does, at exit.
inline const std::filesystem::path& scratch_dir() {
  struct Dir {
    std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) / ("fsd_test_" + std::to_string(::getpid()));
    Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);  // left by an earlier process with the same pid (kept, or killed)
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      if (std::getenv("FSD_KEEP_TEST_FILES")) return;
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

// scratch_dir()/name.
inline std::string scratch_path(const std::string& name) { return (scratch_dir() / name).string(); }

}  // namespace fsd::test
