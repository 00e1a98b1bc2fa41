#include "drivers/sim/virtual_car.hpp"

#include <cmath>

#include "common/logging.hpp"
#include "drivers/sim/vehicle/model_mismatch.hpp"

namespace fsd::sim {

const ConfigSection<SimRunConfig>& sim_run_section() {
  static const auto s = ConfigSection<SimRunConfig>("sim")
                            .number("physics_rate_hz", &SimRunConfig::physics_rate_hz, 200.0, 5000.0, "Hz",
                                    "Fixed integration rate of the vehicle model (≥ 200 Hz).")
                            .boolean("enable_lidar", &SimRunConfig::lidar, "Simulate the VLP-16 (ray casting).")
                            .boolean("enable_gnss", &SimRunConfig::gnss, "Simulate the GNSS-INS receiver.")
                            .boolean("enable_camera", &SimRunConfig::camera, "Simulate the camera (rendering, JPEG).");
  return s;
}

void describe_virtual_car_config(ConfigSchema& schema) {
  describe_car(schema);
  sim_run_section().describe(schema);
  vehicle_section().describe(schema);
  world_section().describe(schema);
  lidar_section().describe(schema);
  gnss_model_section().describe(schema);
  vcu_standin_section().describe(schema);
  camera_section().describe(schema);
  model_mismatch_section().describe(schema);
  describe_fault_schedule(schema);
}

VirtualCarSettings read_virtual_car_settings(const Config& cfg) {
  VirtualCarSettings s;
  s.run = sim_run_section().read(cfg);
  s.vehicle = vehicle_section().read(cfg);
  s.world = world_section().read(cfg);
  s.lidar = lidar_section().read(cfg);
  s.gnss = gnss_model_section().read(cfg);
  s.vcu = vcu_standin_section().read(cfg);
  s.camera = camera_section().read(cfg);
  s.faults = read_fault_schedule(cfg);
  const ModelMismatch mismatch = model_mismatch_section().read(cfg);
  apply_car(read_car(cfg), mismatch, s.vehicle, s.lidar, s.gnss);
  s.camera_roll_error = mismatch.camera_roll;
  s.camera_pitch_error = mismatch.camera_pitch;
  s.camera_yaw_error = mismatch.camera_yaw;
  return s;
}

namespace {
VcuStandinConfig seeded(VcuStandinConfig c, std::uint64_t seed) {
  c.seed = static_cast<int>(seed % 1000000007ULL);
  return c;
}
}  // namespace

VirtualCar::VirtualCar(const Track& track, const VirtualCarSettings& settings, std::uint64_t seed, SensorSinks sinks)
    : s_(settings),
      world_(track, settings.world, seed),
      vehicle_(settings.vehicle),
      // Status frames go through the (cuttable) link; the lambda runs only after construction.
      vcu_(seeded(settings.vcu, seed),
           [this](Stamp t, std::span<const std::uint8_t> b) {
             if (sinks_.vcu_status && !faults_.active(FaultKind::VcuLink, t)) sinks_.vcu_status(t, b);
           }),
      sinks_(std::move(sinks)),
      faults_(settings.faults, track),
      dt_(1.0 / settings.run.physics_rate_hz) {
  vehicle_.reset(track.start, 0.0, 0.0);
  steps_.push(vehicle_.truth());
  // Each sensor gets its own seed stream so enabling one does not change another's noise.
  if (s_.run.lidar) lidar_ = std::make_unique<LidarModel>(s_.lidar, world_, seed * 7919 + 1, 0.0);
  if (s_.run.gnss) gnss_ = std::make_unique<GnssModel>(s_.gnss, seed * 7919 + 2);
  if (s_.run.camera) {
    CameraConfig mounted = s_.camera;
    mounted.roll += s_.camera_roll_error;
    mounted.pitch += s_.camera_pitch_error;
    mounted.yaw += s_.camera_yaw_error;
    camera_ = std::make_unique<CameraModel>(mounted, world_, seed * 7919 + 3, 0.0);
  }
  // A LiDAR outage: the packets are produced (the model's clock runs on) but never leave the sensor.
  if (sinks_.lidar) {
    sinks_.lidar = [this, out = sinks_.lidar](Stamp t, std::span<const std::uint8_t> b) {
      if (!faults_.active(FaultKind::Lidar, t)) out(t, b);
    };
  }
  // A camera outage: the frames are rendered on the camera's clock but never sent.
  if (sinks_.camera) {
    sinks_.camera = [this, out = sinks_.camera](Stamp t, std::span<const std::uint8_t> b) {
      if (!faults_.active(FaultKind::Camera, t)) out(t, b);
    };
  }
}

void VirtualCar::feed_vcu(Stamp t, std::span<const std::uint8_t> bytes) {
  if (!faults_.active(FaultKind::VcuLink, t)) vcu_.feed(t, bytes);
}

VehicleTruth VirtualCar::truth_at(Stamp t) const { return steps_.at(t); }

void VirtualCar::log_new_hits() {
  // Which cone and where the car was: a cone count alone does not say which corner went wrong.
  const VehicleTruth& v = vehicle_.truth();
  std::vector<const WorldCone*> fresh;
  for (const auto& c : world_.cones())
    if (c.knocked && c.hit_time == v.t) fresh.push_back(&c);
  for (const WorldCone* c : fresh)
    logger("sim")->info(
        "cone hit at {:.2f} s: {} cone at ({:.2f}, {:.2f}); car at ({:.2f}, {:.2f}) heading {:.2f} rad, {:.1f} m/s",
        v.t, to_string(c->colour), c->base.x(), c->base.y(), v.pose.x, v.pose.y, v.pose.yaw, v.speed());
}

void VirtualCar::advance_to(Stamp t) {
  while (vehicle_.truth().t + dt_ <= t + 1e-9) {
    const Stamp now = vehicle_.truth().t;
    const ActuatorOutput& out = vcu_.step(now, vehicle_.truth());
    ActuatorCommand cmd;
    cmd.steering = out.steering_request;
    cmd.target_speed = out.target_speed;
    cmd.max_brake = out.max_brake;
    cmd.ebs = out.ebs;
    cmd.drive_enabled = out.drive_enabled;
    vehicle_.step(dt_, cmd);
    steps_.push(vehicle_.truth());
    const auto fp = vehicle_.footprint();
    if (world_.update_hits(fp, vehicle_.truth().t) > 0) log_new_hits();
    const Stamp t1 = vehicle_.truth().t;
    faults_.on_truth(t1, vehicle_.truth().pose.position());
    if (gnss_ && !gnss_outage_set_) {
      if (const auto w = faults_.window(FaultKind::Gnss)) {
        gnss_->set_outage(w->start, w->end - w->start, s_.faults.gnss.mode);
        gnss_outage_set_ = true;
      }
    }
    if (lidar_ && sinks_.lidar)
      lidar_->advance_to(
          t1, [this](Stamp ts) { return truth_at(ts).body_pose3(); }, sinks_.lidar);
    if (camera_ && sinks_.camera)
      camera_->advance_to(
          t1, [this](Stamp ts) { return truth_at(ts).body_pose3(); }, sinks_.camera);
    if (gnss_ && sinks_.gnss)
      gnss_->advance_to(
          t1, [this](Stamp ts) { return truth_at(ts); }, sinks_.gnss);
  }
}

std::vector<ConeReturns> VirtualCar::take_lidar_cone_returns() {
  if (!lidar_) return {};
  auto returns = lidar_->take_cone_returns();
  std::erase_if(returns, [this](const ConeReturns& r) { return faults_.active(FaultKind::Lidar, r.t); });
  return returns;
}

std::vector<Cone> VirtualCar::standing_cones() const {
  std::vector<Cone> out;
  for (std::size_t i = 0; i < world_.cones().size(); ++i) {
    const auto& wc = world_.cones()[i];
    if (wc.knocked) continue;
    Cone c;
    c.position = wc.base;
    c.colour = wc.colour;
    c.id = cone_id(static_cast<int>(i));
    out.push_back(c);
  }
  return out;
}

}  // namespace fsd::sim
