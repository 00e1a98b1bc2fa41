#pragma once
// Configuration of the virtual car's camera (keys under "sim.camera") and the pinhole geometry derived from it.
//
// Frames: the mount pose (x, y, z, roll, pitch, yaw; Z-Y-X like the LiDAR mount) places a camera body frame with
// x forward, y left, z up on the vehicle body frame; pitch positive tilts the view down. The optical frame used
// for projection is the OpenCV one: x right, y down, z along the optical axis. A point (X, Y, Z) in the optical
// frame lands on pixel u = fx·X/Z + cx, v = fy·Y/Z + cy, with pixel centres at integer coordinates.
#include "common/camera_geometry.hpp"
#include "common/config.hpp"
#include "common/geometry.hpp"

namespace fsd::sim {

struct CameraConfig {
  double rate = 20.0;  // frames per second
  int width = 640;
  int height = 480;
  // Intrinsics: fx/fy ≤ 0 derive a square pixel from the horizontal field of view; cx/cy < 0 put the principal
  // point at the image centre.
  double hfov = 1.22;  // rad (70°)
  double fx = 0.0, fy = 0.0;
  double cx = -1.0, cy = -1.0;
  // Mount on the vehicle body frame (rear-axle centre on the ground): on the main hoop, looking slightly down.
  double x = 0.5, y = 0.0, z = 1.05;
  double roll = 0.0, pitch = 0.10, yaw = 0.0;
  double latency = 0.03;     // s from capture to the frame leaving the camera
  double pixel_noise = 2.0;  // σ of the sensor noise, 8-bit levels
  double blur = 0.6;         // σ of the optical blur, px (0 = none)
  // Lighting: exposure gain and white balance (+ warmer/redder, − cooler/bluer) around their base values,
  // varying smoothly over lighting_period, with occasional cloud shadows and bright spells.
  double gain = 1.0;
  double white_balance = 0.0;
  double gain_variation = 0.2;
  double white_balance_variation = 0.05;
  double lighting_period = 8.0;           // s
  double light_event_probability = 0.15;  // chance of a shadow or bright spell in each lighting period
  double light_event_depth = 0.35;        // relative exposure change of a shadow (a bright spell: half of it)
  double sun_azimuth = 2.2;               // rad, map frame, counter-clockwise from +x
  double sun_elevation = 0.8;             // rad above the horizon
  int jpeg_quality = 85;
  double draw_distance = 80.0;  // m: farther objects are not drawn
};

const ConfigSection<CameraConfig>& camera_section();  // prefix "sim.camera"

struct PinholeIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
};
PinholeIntrinsics camera_intrinsics(const CameraConfig& cfg);

// Body ← camera optical frame (x right, y down, z forward).
Pose3 camera_mount(const CameraConfig& cfg);

// The calibration a perfect calibration of this camera would give (what the camera stage is handed in a simulated
// run: the model mismatch is in the rendering, not in the mount).
CameraCalibration calibration_of(const CameraConfig& cfg);

}  // namespace fsd::sim
