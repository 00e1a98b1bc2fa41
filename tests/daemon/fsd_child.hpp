#pragma once
// The fsd binary in a child process, as a user runs it, for tests that talk to it while it runs (its dashboard,
// its devices): output to a file, read while it runs; killed by the destructor if the test did not wait for it.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fsd::test {

// The fsd binary in a child process, stdout and stderr to a file.
class Fsd {
 public:
  Fsd(const std::vector<std::string>& args, std::string log) : log_(std::move(log)) {
    std::ofstream(log_, std::ios::trunc).flush();  // never read an earlier run's output
    pid_ = ::fork();
    if (pid_ == 0) {
      FILE* f = std::freopen(log_.c_str(), "w", stdout);
      if (!f || ::dup2(::fileno(stdout), 2) < 0) ::_exit(127);
      std::vector<char*> argv{const_cast<char*>(FSD_BINARY)};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(FSD_BINARY, argv.data());
      ::_exit(127);
    }
  }
  ~Fsd() {
    if (pid_ > 0 && status_ < 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  // Exit status, or -1 when the process is still running after `timeout` (then it is killed).
  int wait(std::chrono::duration<double> timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (status_ < 0 && std::chrono::steady_clock::now() < end) {
      int st = 0;
      if (::waitpid(pid_, &st, WNOHANG) == pid_)
        status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      else
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return status_;
  }
  std::string output() const {
    std::ifstream f(log_);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
  // Waits until the output matches `re`; returns the first capture group (empty on timeout or exit).
  std::string wait_for(const std::regex& re, std::chrono::duration<double> timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    std::smatch m;
    for (;;) {
      const bool exited = wait(std::chrono::seconds(0)) >= 0;
      const std::string out = output();
      if (std::regex_search(out, m, re)) return m.size() > 1 ? m[1].str() : m[0].str();
      if (exited || std::chrono::steady_clock::now() >= end) return {};
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

 private:
  std::string log_;
  pid_t pid_ = -1;
  int status_ = -1;
};

}  // namespace fsd::test
