#include "drivers/sim/sensors/camera_model_config.hpp"

#include <cmath>

#include "common/rotation.hpp"

namespace fsd::sim {

const ConfigSection<CameraConfig>& camera_section() {
  using C = CameraConfig;
  static const auto s =
      ConfigSection<C>("sim.camera")
          .number("rate", &C::rate, 10.0, 60.0, "Hz", "Frame rate (FS cameras: 20..30 Hz).")
          .integer("width", &C::width, 160, 1920, "px", "Image width.")
          .integer("height", &C::height, 120, 1080, "px", "Image height.")
          .number("hfov", &C::hfov, 0.3, 2.6, "rad", "Horizontal field of view, used when fx/fy are 0.")
          .number("fx", &C::fx, 0.0, 10000.0, "px", "Focal length along u; 0 = from hfov.")
          .number("fy", &C::fy, 0.0, 10000.0, "px", "Focal length along v; 0 = equal to fx.")
          .number("cx", &C::cx, -1.0, 4000.0, "px", "Principal point u; -1 = image centre.")
          .number("cy", &C::cy, -1.0, 4000.0, "px", "Principal point v; -1 = image centre.")
          .number("x", &C::x, -5.0, 5.0, "m",
                  "Mount position on the body frame (rear-axle centre on the ground): forward.")
          .number("y", &C::y, -2.0, 2.0, "m", "Mount position: left.")
          .number("z", &C::z, 0.1, 3.0, "m", "Mount position: height above the ground.")
          .number("roll", &C::roll, -0.5, 0.5, "rad", "Mount roll (Z-Y-X).")
          .number("pitch", &C::pitch, -0.5, 0.8, "rad", "Mount pitch, positive looks down.")
          .number("yaw", &C::yaw, -3.15, 3.15, "rad", "Mount yaw.")
          .number("latency", &C::latency, 0.0, 0.5, "s", "From capture to the frame leaving the camera.")
          .number("pixel_noise", &C::pixel_noise, 0.0, 30.0, "", "Sigma of the sensor noise in 8-bit levels.")
          .number("blur", &C::blur, 0.0, 5.0, "px", "Sigma of the optical blur; 0 = sharp.")
          .number("gain", &C::gain, 0.2, 3.0, "", "Base exposure gain (1 = nominal).")
          .number("white_balance", &C::white_balance, -0.3, 0.3, "",
                  "Base colour temperature shift: red gain 1+w, blue gain 1-w (+ warm, - cool).")
          .number("gain_variation", &C::gain_variation, 0.0, 0.8, "", "Relative amplitude of the slow exposure drift.")
          .number("white_balance_variation", &C::white_balance_variation, 0.0, 0.3, "",
                  "Amplitude of the slow white balance drift.")
          .number("lighting_period", &C::lighting_period, 0.5, 600.0, "s",
                  "Time scale of the lighting drift and events.")
          .number("light_event_probability", &C::light_event_probability, 0.0, 1.0, "",
                  "Chance of a cloud shadow or bright spell in each lighting period.")
          .number("light_event_depth", &C::light_event_depth, 0.0, 0.9, "",
                  "Relative exposure drop of a cloud shadow (a bright spell raises it by half as much).")
          .number("sun_azimuth", &C::sun_azimuth, -6.3, 6.3, "rad",
                  "Sun direction in the map, counter-clockwise from +x.")
          .number("sun_elevation", &C::sun_elevation, 0.05, 1.57, "rad", "Sun elevation above the horizon.")
          .integer("jpeg_quality", &C::jpeg_quality, 10, 100, "", "JPEG quality of the emitted frames (MJPEG camera).")
          .number("draw_distance", &C::draw_distance, 5.0, 300.0, "m", "Objects farther than this are not drawn.");
  return s;
}

PinholeIntrinsics camera_intrinsics(const CameraConfig& cfg) {
  PinholeIntrinsics k;
  k.fx = cfg.fx > 0.0 ? cfg.fx : (cfg.width / 2.0) / std::tan(cfg.hfov / 2.0);
  k.fy = cfg.fy > 0.0 ? cfg.fy : k.fx;
  k.cx = cfg.cx >= 0.0 ? cfg.cx : (cfg.width - 1) / 2.0;
  k.cy = cfg.cy >= 0.0 ? cfg.cy : (cfg.height - 1) / 2.0;
  return k;
}

Pose3 camera_mount(const CameraConfig& cfg) {
  Pose3 T = pose_zyx(Vec3(cfg.x, cfg.y, cfg.z), cfg.yaw, cfg.pitch, cfg.roll);
  T.linear() = T.linear() * mount_from_optical();
  return T;
}

CameraCalibration calibration_of(const CameraConfig& cfg) {
  const PinholeIntrinsics k = camera_intrinsics(cfg);
  CameraIntrinsics in;
  in.width = cfg.width;
  in.height = cfg.height;
  in.K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  CameraCalibration c;
  c.intrinsics = in;
  c.extrinsics = CameraMount{cfg.x, cfg.y, cfg.z, cfg.roll, cfg.pitch, cfg.yaw};
  return c;
}

}  // namespace fsd::sim
