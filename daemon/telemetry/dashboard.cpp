#include "daemon/telemetry/dashboard.hpp"

#include "common/car.hpp"
#include "common/clock.hpp"
#include "common/params.hpp"
#include "daemon/telemetry/run_metrics.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "web/config.hpp"
#include "web/server.hpp"

namespace fsd {

Dashboard::Dashboard(const Config& config, ParamRegistry& params, Clock& clock, bool truth_channels) {
  const web::WebConfig wc = web::web_section().read(config);
  bind_ = wc.bind;
  server_ = std::make_unique<web::WebServer>(wc, params, clock);
  telemetry_ = std::make_unique<Telemetry>(*server_, truth_channels, web::car_shape_of(read_car(config)));
  metrics_ = std::make_unique<RunMetrics>(server_->metrics());
  // Before the server's threads start: spdlog's sink lists must not change while anyone logs.
  log_forwarding_ = std::make_unique<LogForwarding>(*server_, telemetry_->channel(web::topics::kLog), clock);
}

Dashboard::~Dashboard() { stop(); }

void Dashboard::start() { server_->start(); }

void Dashboard::stop() {
  if (stopped_) return;
  stopped_ = true;
  telemetry_->stop();
  server_->stop();
  log_forwarding_->detach();
}

std::string Dashboard::url() const {
  const std::string host = bind_ == "0.0.0.0" ? "localhost" : bind_;
  return "http://" + host + ":" + std::to_string(server_->port()) + "/";
}

}  // namespace fsd
