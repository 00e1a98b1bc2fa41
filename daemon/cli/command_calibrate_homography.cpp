#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "drivers/camera/camera_calibration.hpp"
#include "drivers/camera/ground_homography.hpp"

namespace fsd {

namespace {
struct CalibrateHomographyArgs {
  std::string image_points, ground_points, out, in;
};

int calibrate_homography(const CalibrateHomographyArgs& a) {
  try {
    HomographyCalibration h;
    h.image_points = parse_point_quad(a.image_points, "--image-points");
    h.ground_points = parse_point_quad(a.ground_points, "--ground-points");
    h.homography = compute_ground_homography(*h.image_points, *h.ground_points);
    CameraCalibration calib = a.in.empty() ? CameraCalibration{} : load_camera_calibration(a.in);
    calib.homography = h;
    save_camera_calibration(calib, a.out);

    const Eigen::Matrix3d& m = h.homography.image_to_ground;
    std::printf("image -> ground homography written to %s\n", a.out.c_str());
    for (int r = 0; r < 3; ++r) std::printf("  [% .9g % .9g % .9g]\n", m(r, 0), m(r, 1), m(r, 2));
    return kExitOk;
  } catch (const HomographyError& e) {
    std::cerr << "fsd calibrate-homography: " << e.what() << "\n";
  } catch (const CalibrationError& e) {
    std::cerr << "fsd calibrate-homography: " << e.what() << "\n";
  }
  return kExitBadInput;
}
}  // namespace

void add_calibrate_homography_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "calibrate-homography",
      "Compute the camera's image <-> ground homography from 4 point pairs (perspective transform) and write the "
      "calibration file");
  static CalibrateHomographyArgs args;
  cmd->add_option("--image-points", args.image_points, "four pixels 'u1,v1;u2,v2;u3,v3;u4,v4'")->required();
  cmd->add_option("--ground-points", args.ground_points,
                  "the same four points on the ground, vehicle frame in metres (x forward, y left): 'x1,y1;...;x4,y4'")
      ->required();
  cmd->add_option("--out", args.out, "calibration file to write (JSON, docs/camera.md)")->required();
  cmd->add_option("--in", args.in, "existing calibration file whose intrinsics and extrinsics are kept");
  cmd->callback([&exit_code] { exit_code = calibrate_homography(args); });
}

}  // namespace fsd
