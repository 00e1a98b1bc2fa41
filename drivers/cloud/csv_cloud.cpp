#include "drivers/cloud/csv_cloud.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

namespace fsd {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Splits at commas into at most `out.size()` fields; returns the number of fields (more than out.size() counted).
std::size_t split(std::string_view line, std::array<std::string_view, 16>& out) {
  std::size_t n = 0;
  while (true) {
    const auto comma = line.find(',');
    const std::string_view field = trim(line.substr(0, comma));
    if (n < out.size()) out[n] = field;
    ++n;
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  return n;
}

bool parse_number(std::string_view s, double& v) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

std::string lower(std::string_view s) {
  std::string o(s);
  std::transform(o.begin(), o.end(), o.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return o;
}

struct Columns {
  int x = -1, y = -1, z = -1, intensity = -1, laser = -1, time = -1;
  std::size_t count = 0;
};

std::string where(const std::string& origin, std::size_t line) { return origin + ":" + std::to_string(line) + ": "; }

}  // namespace

CsvCloud parse_csv_cloud(std::string_view text, const std::string& origin, const CsvCloudLimits& limits) {
  CsvCloud out;
  Columns col;
  bool have_layout = false;
  std::array<std::string_view, 16> f{};
  std::size_t line_no = 0;
  while (!text.empty()) {
    const auto nl = text.find('\n');
    const std::string_view raw = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const std::size_t n = split(line, f);
    if (n > f.size()) throw CloudError(where(origin, line_no) + "more than 16 fields");
    if (!have_layout) {
      have_layout = true;
      double v = 0;
      const bool numeric = std::all_of(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(n),
                                       [&](std::string_view s) { return parse_number(s, v); });
      if (!numeric) {
        // A header: columns by name.
        out.header = true;
        col.count = n;
        for (std::size_t k = 0; k < n; ++k) {
          const std::string name = lower(f[k]);
          int* slot = name == "x"                                                      ? &col.x
                      : name == "y"                                                    ? &col.y
                      : name == "z"                                                    ? &col.z
                      : (name == "intensity" || name == "reflectivity" || name == "i") ? &col.intensity
                      : (name == "laser" || name == "ring")                            ? &col.laser
                      : name == "t_us"                                                 ? &col.time
                                                                                       : nullptr;
          if (!slot) continue;  // another column (lidar-dump's azimuth_deg, distance_m): ignored
          if (*slot >= 0) throw CloudError(where(origin, line_no) + "column '" + name + "' appears twice");
          *slot = static_cast<int>(k);
        }
        if (col.x < 0 || col.y < 0 || col.z < 0)
          throw CloudError(where(origin, line_no) + "header needs columns x, y and z (found '" + std::string(line) +
                           "')");
        continue;
      }
      if (n != 3 && n != 4)
        throw CloudError(where(origin, line_no) + "expected x,y,z or x,y,z,intensity, found " + std::to_string(n) +
                         " fields");
      col.count = n;
      col.x = 0, col.y = 1, col.z = 2, col.intensity = n == 4 ? 3 : -1;
    }
    if (n != col.count)
      throw CloudError(where(origin, line_no) + "expected " + std::to_string(col.count) + " fields, found " +
                       std::to_string(n));
    ++out.rows;
    const auto number = [&](int c, const char* name) {
      double v = 0;
      if (!parse_number(f[static_cast<std::size_t>(c)], v))
        throw CloudError(where(origin, line_no) + name + " is not a number: '" +
                         std::string(f[static_cast<std::size_t>(c)]) + "'");
      return v;
    };
    const double x = number(col.x, "x"), y = number(col.y, "y"), z = number(col.z, "z");
    const double intensity = col.intensity >= 0 ? number(col.intensity, "intensity") : 0.0;
    const double laser = col.laser >= 0 ? number(col.laser, "laser") : 0.0;
    const double t_us = col.time >= 0 ? number(col.time, "t_us") : 0.0;
    if (col.laser >= 0 && !(laser >= 0 && laser <= 255 && laser == std::floor(laser)))
      throw CloudError(where(origin, line_no) + "laser must be an integer 0..255");
    const double m = limits.max_coordinate;
    // Intensities beyond a float's range (or any sensor's) and times beyond a year of µs are not data either.
    if (!(std::abs(x) <= m && std::abs(y) <= m && std::abs(z) <= m) || !(std::abs(intensity) <= 1e6) ||
        !(std::abs(t_us) <= 1e15)) {
      ++out.invalid;
      continue;
    }
    if (out.scan.points.size() >= limits.max_points)
      throw CloudError(origin + ": more than " + std::to_string(limits.max_points) + " points");
    Point p;
    p.x = static_cast<float>(x), p.y = static_cast<float>(y), p.z = static_cast<float>(z);
    p.intensity = static_cast<float>(intensity);
    p.ring = static_cast<std::uint16_t>(laser);
    p.t = t_us * 1e-6;
    p.distance = static_cast<float>(std::sqrt(x * x + y * y + z * z));
    // Sensor convention: clockwise from +x seen from above, [0, 2π).
    double az = -std::atan2(y, x);
    if (az < 0) az += 2 * std::numbers::pi;
    p.azimuth = static_cast<float>(az);
    out.scan.points.push_back(p);
  }
  if (out.scan.points.empty())
    throw CloudError(origin + ": no valid point" +
                     (out.rows > 0 ? " (" + std::to_string(out.invalid) + " rows with coordinates not finite)" : ""));
  out.has_intensity = col.intensity >= 0;
  out.has_lasers = col.laser >= 0;
  out.has_times = col.time >= 0;
  out.scan.stamp = out.scan.points.front().t;
  return out;
}

CsvCloud load_csv_cloud(const std::filesystem::path& file, const CsvCloudLimits& limits) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw CloudError(file.string() + ": cannot read (" + ec.message() + ")");
  if (size > limits.max_bytes)
    throw CloudError(file.string() + ": " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(limits.max_bytes) + " a cloud may have");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CloudError(file.string() + ": cannot open");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) throw CloudError(file.string() + ": read failed");
  return parse_csv_cloud(text, file.string(), limits);
}

}  // namespace fsd
