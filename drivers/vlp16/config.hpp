#pragma once
// Configuration of the VLP-16 driver (section "drivers.vlp16").
#include <string>

#include "common/car.hpp"
#include "common/config.hpp"
#include "common/geometry.hpp"

namespace fsd {

struct Vlp16Config {
  std::string address = "0.0.0.0";  // local address the UDP sockets bind to
  int data_port = 2368;
  int position_port = 8308;
  int receive_buffer_bytes = 4 << 20;  // SO_RCVBUF; ~2.6 s of data packets
  double frame_cut_deg = 0.0;          // a frame ends when the azimuth crosses this angle
  double min_range = 0.5;              // m; closer returns are dropped (sensor's blind zone, own car)
  double max_range = 130.0;            // m; farther returns are dropped
  std::string laser_table;             // CSV like ../shared/data/vlp16/vlp16_lasers.csv; "" = built-in table
  // Mount on the vehicle body frame (rear-axle centre on the ground, x forward, z up): what the stack places the
  // points with. The car's description (car.lidar): on the nose ahead of the front wheels.
  SensorMount mount = CarDescription{}.lidar;
  Pose3 body_from_sensor() const { return mount.body_from_sensor(); }  // body ← sensor
};

const ConfigSection<Vlp16Config>& vlp16_section();
// The section plus the mount of the car's description (car.lidar).
Vlp16Config read_vlp16_config(const Config& config);

}  // namespace fsd
