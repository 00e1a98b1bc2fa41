#pragma once
// The pit-lane dashboard of a run (DESIGN.md §1, §6): the web server (HTTP + WebSocket on one port), the telemetry
// thread that feeds its channels, the run's /metrics and the log lines on /log, started together and stopped in
// the right order. The same for the virtual car and the real one; only the virtual car adds the /truth channels.
#include <memory>
#include <string>

#include "common/config.hpp"

namespace fsd {

class Clock;
class LogForwarding;
class ParamRegistry;
class RunMetrics;
class Telemetry;
namespace web {
class WebServer;
}

class Dashboard {
 public:
  // `params` and `clock` must outlive the dashboard. Nothing listens before start().
  Dashboard(const Config& config, ParamRegistry& params, Clock& clock, bool truth_channels);
  ~Dashboard();  // stop()
  Dashboard(const Dashboard&) = delete;
  Dashboard& operator=(const Dashboard&) = delete;

  // Binds the port and starts serving; throws std::runtime_error when the port cannot be bound.
  void start();
  // Telemetry first (no more messages), then the server, then the log forwarding. Idempotent.
  void stop();

  Telemetry& telemetry() { return *telemetry_; }
  RunMetrics& metrics() { return *metrics_; }
  // Where a browser on this machine finds it (the bound port: web.port 0 picks a free one).
  std::string url() const;

 private:
  std::string bind_;
  std::unique_ptr<web::WebServer> server_;
  std::unique_ptr<Telemetry> telemetry_;
  std::unique_ptr<RunMetrics> metrics_;
  std::unique_ptr<LogForwarding> log_forwarding_;
  bool stopped_ = false;
};

}  // namespace fsd
