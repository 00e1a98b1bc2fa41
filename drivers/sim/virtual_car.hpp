#pragma once
// The virtual car: world, vehicle dynamics, VCU stand-in and sensor models stepped together at a fixed physics
// rate. Sensors write the bytes of the real devices to sinks; the daemon sends the VCU's bytes in through
// feed_vcu(). The car never reads a clock: its owner advances it (lockstep) or paces it in real time.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/config.hpp"
#include "common/track.hpp"
#include "common/types.hpp"
#include "drivers/sim/fault_schedule.hpp"
#include "drivers/sim/sensors/camera_model.hpp"
#include "drivers/sim/sensors/gnss_model.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/sensors/sink.hpp"
#include "drivers/sim/vcu_standin.hpp"
#include "drivers/sim/vehicle/truth_history.hpp"
#include "drivers/sim/vehicle/vehicle_model.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim {

struct SimRunConfig {
  double physics_rate_hz = 400.0;
  bool lidar = true;  // the VLP-16 model (costly: off when only truth perception is used)
  bool gnss = true;
  bool camera = true;  // the camera model (rendering + JPEG: costly)
};
const ConfigSection<SimRunConfig>& sim_run_section();  // prefix "sim"

// Every setting of the virtual car, read from the sections of the configuration.
struct VirtualCarSettings {
  SimRunConfig run;
  VehicleParams vehicle;
  WorldConfig world;
  LidarConfig lidar;
  GnssModelConfig gnss;
  VcuStandinConfig vcu;
  CameraConfig camera;  // as calibrated: what the daemon is told
  // The camera as it renders turned by these (rad; sim.mismatch.camera_roll, _pitch, _yaw) from `camera`.
  double camera_roll_error = 0, camera_pitch_error = 0, camera_yaw_error = 0;
  FaultScheduleConfig faults;
};
VirtualCarSettings read_virtual_car_settings(const Config& cfg);
void describe_virtual_car_config(ConfigSchema& schema);

struct SensorSinks {
  ByteSink lidar;       // VLP-16 UDP payloads (1206 bytes each)
  ByteSink gnss;        // NMEA bytes as they leave the receiver's serial port
  ByteSink vcu_status;  // VCU protocol bytes towards the daemon
  ByteSink camera;      // JPEG frames as an MJPEG camera sends them
};

class VirtualCar {
 public:
  VirtualCar(const Track& track, const VirtualCarSettings& settings, std::uint64_t seed, SensorSinks sinks);

  // Bytes from the daemon to the VCU, arriving at time t (lost while the fault schedule cuts the VCU link).
  void feed_vcu(Stamp t, std::span<const std::uint8_t> bytes);
  // Integrates physics in fixed steps up to t and lets every sensor emit what it produced meanwhile; the fault
  // schedule silences the sensors and the link in its windows.
  void advance_to(Stamp t);

  Stamp now() const { return truth().t; }
  const VehicleTruth& truth() const { return vehicle_.truth(); }
  const VehicleModel& vehicle() const { return vehicle_; }
  VcuStandin& vcu() { return vcu_; }
  const World& world() const { return world_; }
  GnssModel* gnss() { return gnss_.get(); }
  const FaultSchedule& faults() const { return faults_; }
  int cones_hit() const { return world_.cones_hit(); }
  // Upright cones in the map frame with their true colours (the truth perception source and the scorecard).
  std::vector<Cone> standing_cones() const;
  // The id a world cone (index into World::cones()) carries in standing_cones() and the truth frames.
  static std::uint32_t cone_id(int index) { return static_cast<std::uint32_t>(index + 1); }
  std::uint64_t lidar_packets() const { return lidar_ ? lidar_->packets_sent() : 0; }
  // The LiDAR's returns from each cone since the last call, as they left the sensor (none in a LiDAR outage, none
  // without the LiDAR model): which cones the sensor could see.
  std::vector<ConeReturns> take_lidar_cone_returns();

 private:
  VehicleTruth truth_at(Stamp t) const;  // interpolated between the physics steps around t (the recent ones)
  void log_new_hits();                   // one line per cone knocked over in the last physics step

  VirtualCarSettings s_;
  World world_;
  VehicleModel vehicle_;
  VcuStandin vcu_;
  std::unique_ptr<LidarModel> lidar_;
  std::unique_ptr<GnssModel> gnss_;
  std::unique_ptr<CameraModel> camera_;
  SensorSinks sinks_;
  FaultSchedule faults_;
  bool gnss_outage_set_ = false;  // the GNSS fault's window has been handed to the receiver model
  TruthHistory steps_;  // the recent physics steps, the newest the vehicle's truth: what the sensors pose from
  double dt_;
};

}  // namespace fsd::sim
