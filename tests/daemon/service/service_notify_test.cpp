// The daemon under a service manager (deploy/fsd.service, Type=notify, WatchdogSec): the test plays systemd. It
// binds the unix datagram socket the daemon is told of in NOTIFY_SOCKET and reads what the kernel delivers there:
// READY=1 once the run is up, then WATCHDOG=1 from the control loop at half of WATCHDOG_USEC; with the loop hung
// (service.test_stall_*, a real stall of the loop's thread) the pings stop, as systemd's watchdog needs them to.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "tests/daemon/fsd_child.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

using Clock = std::chrono::steady_clock;

struct Notification {
  double t;  // s since the socket was bound
  std::string text;
};

// The socket systemd would hold: bound before the daemon starts, read with a timeout.
class NotifySocket {
 public:
  explicit NotifySocket(std::string path) : path_(std::move(path)) {
    ::unlink(path_.c_str());
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path_.c_str());
    ok_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    timeval tv{0, 50000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    t0_ = Clock::now();
  }
  ~NotifySocket() {
    if (fd_ >= 0) ::close(fd_);
    ::unlink(path_.c_str());
  }
  bool ok() const { return ok_; }
  // Everything that arrives within `d`.
  void read_for(std::chrono::duration<double> d, std::vector<Notification>& out) {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(d);
    char buf[4096];
    while (Clock::now() < end) {
      const auto n = ::recv(fd_, buf, sizeof buf, 0);
      if (n > 0) out.push_back({std::chrono::duration<double>(Clock::now() - t0_).count(), std::string(buf, n)});
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
  bool ok_ = false;
  Clock::time_point t0_;
};

bool has(const Notification& n, const char* what) { return n.text.find(what) != std::string::npos; }

// The daemon started as systemd starts it: NOTIFY_SOCKET and WATCHDOG_USEC in its environment.
std::unique_ptr<test::Fsd> start(const std::string& socket, const std::string& config_json, const std::string& name) {
  const auto cfg = test::scratch_path(name + ".json");
  std::ofstream(cfg) << config_json;
  ::setenv("NOTIFY_SOCKET", socket.c_str(), 1);
  ::setenv("WATCHDOG_USEC", "200000", 1);  // WatchdogSec=0.2s: a ping every 100 ms
  ::unsetenv("WATCHDOG_PID");
  auto fsd = std::make_unique<test::Fsd>(std::vector<std::string>{"run", "--sim", "--port", "0", "--config", cfg,
                                                                  "--track", "../shared/tracks/epfl_track_1.csv"},
                                         test::scratch_path(name + ".log"));
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  return fsd;
}

std::vector<double> watchdog_times(const std::vector<Notification>& got) {
  std::vector<double> t;
  for (const auto& n : got)
    if (has(n, "WATCHDOG=1")) t.push_back(n.t);
  return t;
}

TEST(ServiceNotify, ReadyThenWatchdogAtHalfTheConfiguredInterval) {
  NotifySocket sock(test::scratch_path("notify.sock"));
  ASSERT_TRUE(sock.ok());
  auto fsd = start(test::scratch_path("notify.sock"), test::truth_sources(), "notify");
  std::vector<Notification> got;
  sock.read_for(std::chrono::seconds(4), got);
  fsd->signal(SIGTERM);
  EXPECT_EQ(fsd->wait(std::chrono::seconds(20)), 0) << fsd->output();
  sock.read_for(std::chrono::milliseconds(200), got);
  ASSERT_FALSE(got.empty()) << fsd->output();
  EXPECT_TRUE(has(got.front(), "READY=1")) << got.front().text;
  const auto pings = watchdog_times(got);
  ASSERT_GE(pings.size(), 10u) << fsd->output();
  // Every 100 ms (half of WATCHDOG_USEC), within the scheduling of a busy machine; never a gap that would trip it.
  const double mean = (pings.back() - pings.front()) / double(pings.size() - 1);
  EXPECT_NEAR(mean, 0.1, 0.02);
  for (std::size_t k = 1; k < pings.size(); ++k) EXPECT_LT(pings[k] - pings[k - 1], 0.2) << "at " << pings[k];
  EXPECT_TRUE(has(got.back(), "STOPPING=1")) << got.back().text;
}

TEST(ServiceNotify, WatchdogStopsWhileTheControlLoopHangs) {
  NotifySocket sock(test::scratch_path("stall.sock"));
  ASSERT_TRUE(sock.ok());
  auto fsd = start(test::scratch_path("stall.sock"),
                   test::truth_sources({{"service", {{"test_stall_at_s", 1.0}, {"test_stall_s", 1.5}}}}), "stall");
  std::vector<Notification> got;
  sock.read_for(std::chrono::seconds(4), got);
  fsd->signal(SIGTERM);
  EXPECT_EQ(fsd->wait(std::chrono::seconds(20)), 0) << fsd->output();
  const auto pings = watchdog_times(got);
  ASSERT_GE(pings.size(), 10u) << fsd->output();
  double longest = 0, at = 0;
  for (std::size_t k = 1; k < pings.size(); ++k)
    if (pings[k] - pings[k - 1] > longest) longest = pings[k] - pings[k - 1], at = pings[k - 1];
  // Silent for the whole hang (systemd, at WatchdogSec 0.2 s, would have killed it), and only then.
  EXPECT_GE(longest, 1.4);
  EXPECT_LT(longest, 2.0);
  const double ready = got.front().t;
  EXPECT_NEAR(at - ready, 1.0, 0.3);
  EXPECT_GT(pings.back(), at + longest) << "the pings resume when the loop runs again";
}

}  // namespace
}  // namespace fsd
