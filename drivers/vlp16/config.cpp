#include "drivers/vlp16/config.hpp"

#include "common/rotation.hpp"

namespace fsd {

const ConfigSection<Vlp16Config>& vlp16_section() {
  static const auto s =
      ConfigSection<Vlp16Config>("drivers.vlp16")
          .string("address", &Vlp16Config::address, {}, "Local IPv4/IPv6 address the VLP-16 UDP sockets bind to.")
          .integer("data_port", &Vlp16Config::data_port, 1, 65535, "",
                   "UDP port of the data packets (sensor default 2368).")
          .integer("position_port", &Vlp16Config::position_port, 1, 65535, "",
                   "UDP port of the position (GPS/PPS) packets (sensor default 8308).")
          .integer("receive_buffer_bytes", &Vlp16Config::receive_buffer_bytes, 65536, 1 << 30, "B",
                   "Socket receive buffer requested (SO_RCVBUF); the kernel may cap it at net.core.rmem_max.")
          .number("frame_cut_deg", &Vlp16Config::frame_cut_deg, 0.0, 359.99, "deg",
                  "Azimuth (sensor convention, clockwise from +x) where one frame ends and the next begins.")
          .number("min_range", &Vlp16Config::min_range, 0.0, 100.0, "m", "Returns closer than this are dropped.")
          .number("max_range", &Vlp16Config::max_range, 1.0, 200.0, "m", "Returns farther than this are dropped.")
          .string(
              "laser_table", &Vlp16Config::laser_table, {},
              "Laser calibration CSV (laser_id,vert_angle_deg,vert_offset_correction_m[,firing_order_in_sequence]); "
              "empty = the VLP-16 manual's table built in.");
  return s;
}

Vlp16Config read_vlp16_config(const Config& config) {
  Vlp16Config c = vlp16_section().read(config);
  c.mount = read_car(config).lidar;
  return c;
}

}  // namespace fsd
