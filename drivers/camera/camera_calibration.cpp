#include "drivers/camera/camera_calibration.hpp"

#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "common/json_fields.hpp"

namespace fsd {

namespace {
using nlohmann::json;

constexpr const char* kFormat = "fsd-camera-calibration";
constexpr int kVersion = 1;
constexpr double kMaxMountOffset = 10.0;  // m: anything farther is not on the car
constexpr int kMaxImageSide = 16384;

using Reader = JsonFields<CalibrationError>;

Eigen::Matrix3d matrix3(const Reader& r, const std::string& field) {
  const json& v = r.at(field);
  if (!v.is_array() || v.size() != 3) r.fail(field, "expected a 3×3 array of numbers (3 rows of 3)");
  Eigen::Matrix3d m;
  for (int row = 0; row < 3; ++row) {
    const auto values = r.numbers(field + "[" + std::to_string(row) + "]", v[static_cast<std::size_t>(row)]);
    if (values.size() != 3)
      r.fail(field, "row " + std::to_string(row) + " has " + std::to_string(values.size()) + " numbers, expected 3");
    for (int c = 0; c < 3; ++c) m(row, c) = values[static_cast<std::size_t>(c)];
  }
  return m;
}

PointQuad quad(const Reader& r, const std::string& field) {
  const json& v = r.at(field);
  if (!v.is_array() || v.size() != 4) r.fail(field, "expected 4 points [a, b]");
  PointQuad q;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto p = r.numbers(field + "[" + std::to_string(i) + "]", v[i]);
    if (p.size() != 2) r.fail(field, "point " + std::to_string(i + 1) + " must have 2 numbers");
    q[i] = Vec2(p[0], p[1]);
  }
  return q;
}

CameraIntrinsics read_intrinsics(const Reader& r) {
  r.only({"width", "height", "K", "distortion"});
  CameraIntrinsics in;
  in.width = r.integer("width", 1, kMaxImageSide);
  in.height = r.integer("height", 1, kMaxImageSide);
  in.K = matrix3(r, "K");
  const Eigen::Matrix3d& K = in.K;
  if (!(K(0, 0) > 0) || !(K(1, 1) > 0)) r.fail("K", "focal lengths K[0][0] and K[1][1] must be positive");
  if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) != 1)
    r.fail("K", "must be upper triangular with K[2][2] = 1: [[fx, s, cx], [0, fy, cy], [0, 0, 1]]");
  if (K(0, 2) < 0 || K(0, 2) > in.width || K(1, 2) < 0 || K(1, 2) > in.height)
    r.fail("K",
           "principal point (" + std::to_string(K(0, 2)) + ", " + std::to_string(K(1, 2)) + ") lies outside the image");
  if (r.has("distortion")) {
    in.distortion = r.numbers("distortion", r.at("distortion"));
    const std::size_t n = in.distortion.size();
    if (n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
      r.fail("distortion", "has " + std::to_string(n) + " coefficients; OpenCV takes 4, 5, 8, 12 or 14");
  }
  return in;
}

CameraMount read_extrinsics(const Reader& r) {
  r.only({"x", "y", "z", "roll", "pitch", "yaw"});
  constexpr double pi = std::numbers::pi;
  CameraMount m;
  m.x = r.number("x", -kMaxMountOffset, kMaxMountOffset);
  m.y = r.number("y", -kMaxMountOffset, kMaxMountOffset);
  m.z = r.number("z", -kMaxMountOffset, kMaxMountOffset);
  m.roll = r.number("roll", -pi, pi);
  m.pitch = r.number("pitch", -pi / 2, pi / 2);
  m.yaw = r.number("yaw", -pi, pi);
  return m;
}

HomographyCalibration read_homography(const Reader& r) {
  r.only({"image_to_ground", "image_points", "ground_points"});
  HomographyCalibration h;
  try {
    h.homography = make_ground_homography(matrix3(r, "image_to_ground"));
  } catch (const HomographyError& e) {
    r.fail("image_to_ground", e.what());
  }
  if (r.has("image_points") != r.has("ground_points"))
    r.fail(r.has("image_points") ? "ground_points" : "image_points", "missing (give both point lists or neither)");
  if (!r.has("image_points")) return h;
  h.image_points = quad(r, "image_points");
  h.ground_points = quad(r, "ground_points");
  for (std::size_t i = 0; i < 4; ++i) {
    const auto g = image_to_ground(h.homography, (*h.image_points)[i]);
    const Vec2 want = (*h.ground_points)[i];
    if (!g || (*g - want).norm() > 0.01 + 1e-3 * want.norm())
      r.fail("image_to_ground", "does not map image point " + std::to_string(i + 1) + " onto ground point " +
                                    std::to_string(i + 1) + " (recompute it with fsd calibrate-homography)");
  }
  return h;
}

json matrix_json(const Eigen::Matrix3d& m) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2)});
  return rows;
}

json quad_json(const PointQuad& q) {
  json a = json::array();
  for (const auto& p : q) a.push_back({p.x(), p.y()});
  return a;
}
}  // namespace

CameraCalibration parse_camera_calibration(const json& j, const std::string& origin) {
  const Reader r(j, origin, "");
  r.only({"format", "version", "intrinsics", "extrinsics", "homography"});
  if (r.has("format") && r.at("format") != kFormat) r.fail("format", std::string("expected \"") + kFormat + "\"");
  if (r.has("version") && r.integer("version", 0, 1000) != kVersion)
    r.fail("version", "unsupported version; this build reads version " + std::to_string(kVersion));
  CameraCalibration c;
  if (r.has("intrinsics")) c.intrinsics = read_intrinsics(r.object("intrinsics"));
  if (r.has("extrinsics")) c.extrinsics = read_extrinsics(r.object("extrinsics"));
  if (r.has("homography")) c.homography = read_homography(r.object("homography"));
  if (!c.intrinsics && !c.extrinsics && !c.homography)
    r.fail("", "holds no calibration: expected at least one of intrinsics, extrinsics, homography");
  return c;
}

json to_json(const CameraCalibration& c) {
  json j = {{"format", kFormat}, {"version", kVersion}};
  if (c.intrinsics) {
    const auto& in = *c.intrinsics;
    j["intrinsics"] = {
        {"width", in.width}, {"height", in.height}, {"K", matrix_json(in.K)}, {"distortion", in.distortion}};
  }
  if (c.extrinsics) {
    const auto& m = *c.extrinsics;
    j["extrinsics"] = {{"x", m.x}, {"y", m.y}, {"z", m.z}, {"roll", m.roll}, {"pitch", m.pitch}, {"yaw", m.yaw}};
  }
  if (c.homography) {
    json h = {{"image_to_ground", matrix_json(c.homography->homography.image_to_ground)}};
    if (c.homography->image_points && c.homography->ground_points) {
      h["image_points"] = quad_json(*c.homography->image_points);
      h["ground_points"] = quad_json(*c.homography->ground_points);
    }
    j["homography"] = h;
  }
  return j;
}

CameraCalibration load_camera_calibration(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw CalibrationError(file.string() + ": cannot open the calibration file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e999
    throw CalibrationError(file.string() + ": not valid JSON: " + e.what());
  }
  return parse_camera_calibration(j, file.string());
}

void save_camera_calibration(const CameraCalibration& c, const std::filesystem::path& file) {
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw CalibrationError(file.string() + ": cannot write (" + tmp.string() + " does not open)");
    out << to_json(c).dump(2) << "\n";
    if (!out.flush()) throw CalibrationError(file.string() + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw CalibrationError(file.string() + ": cannot replace the file: " + ec.message());
  }
}

}  // namespace fsd
