#include "common/track.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace fsd {

ColourConvention ColourConvention::named(const std::string& name) {
  if (name == "fsg") return {};
  if (name == "fsac") return {"fsac", ConeColour::Red, ConeColour::Blue, ConeColour::Yellow, ConeColour::Orange};
  throw std::invalid_argument("unknown colour convention '" + name + "' (fsg, fsac)");
}

ConeColour ColourConvention::colour_of(ConeRole role) const {
  switch (role) {
    case ConeRole::Left:
      return left;
    case ConeRole::Right:
      return right;
    case ConeRole::Timing:
      return timing;
    case ConeRole::Other:
      return other;
    default:
      return ConeColour::Unknown;
  }
}

ConeRole ColourConvention::role_of(ConeColour colour) const {
  if (colour == ConeColour::Unknown) return ConeRole::Unknown;
  if (colour == left) return ConeRole::Left;
  if (colour == right) return ConeRole::Right;
  if (colour == timing) return ConeRole::Timing;
  if (colour == other) return ConeRole::Other;
  return ConeRole::Unknown;
}

std::size_t Track::count(ConeRole role) const {
  return static_cast<std::size_t>(
      std::count_if(cones.begin(), cones.end(), [&](const TrackCone& c) { return c.role == role; }));
}

std::vector<Cone> cones_of(const Track& track) {
  std::vector<Cone> out;
  out.reserve(track.cones.size());
  for (const auto& c : track.cones) {
    Cone k;
    k.position = Vec3(c.position.x(), c.position.y(), 0);
    k.colour = c.colour;
    out.push_back(k);
  }
  return out;
}

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t");
    const auto e = cell.find_last_not_of(" \t");
    out.push_back(b == std::string::npos ? std::string{} : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

Track parse_track(const std::string& text, const std::string& origin, const ColourConvention& convention) {
  Track track;
  track.name = std::filesystem::path(origin).stem().string();
  track.convention = convention;

  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  auto fail = [&](const std::string& what) -> TrackError {
    return TrackError(origin + ":" + std::to_string(lineno) + ": " + what);
  };

  static constexpr std::array<const char*, 7> kColumns{
      "tag", "x", "y", "direction", "x_variance", "y_variance", "xy_covariance"};
  std::array<int, kColumns.size()> col{};
  bool have_header = false, have_start = false;

  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const auto cells = split_csv(line);
    if (!have_header) {
      for (std::size_t k = 0; k < kColumns.size(); ++k) {
        const auto it = std::find(cells.begin(), cells.end(), kColumns[k]);
        // The covariance columns are optional in hand-written files; the others are not.
        if (it == cells.end()) {
          if (k >= 4) {
            col[k] = -1;
            continue;
          }
          throw fail(std::string("missing column '") + kColumns[k] + "' in header");
        }
        col[k] = static_cast<int>(it - cells.begin());
      }
      have_header = true;
      continue;
    }
    auto number = [&](std::size_t k) -> double {
      if (col[k] < 0) return 0.0;
      if (static_cast<std::size_t>(col[k]) >= cells.size())
        throw fail(std::string("missing value for column '") + kColumns[k] + "'");
      const std::string& s = cells[static_cast<std::size_t>(col[k])];
      double v = 0;
      const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec != std::errc{} || p != s.data() + s.size() || !std::isfinite(v))
        throw fail(std::string("bad number '") + s + "' in column '" + kColumns[k] + "'");
      return v;
    };
    if (static_cast<std::size_t>(col[0]) >= cells.size()) throw fail("missing tag");
    const std::string& tag = cells[static_cast<std::size_t>(col[0])];
    const double x = number(1), y = number(2), dir = number(3);
    if (tag == "car_start") {
      if (have_start) throw fail("second car_start row");
      track.start = {x, y, wrap_angle(dir)};
      have_start = true;
      continue;
    }
    TrackCone cone;
    if (tag == "blue")
      cone.role = ConeRole::Left;
    else if (tag == "yellow")
      cone.role = ConeRole::Right;
    else if (tag == "orange")
      cone.role = ConeRole::Other;
    else if (tag == "big_orange")
      cone.role = ConeRole::Timing;
    else
      throw fail("unknown tag '" + tag + "' (blue, yellow, orange, big_orange, car_start)");
    cone.position = {x, y};
    cone.colour = convention.colour_of(cone.role);
    cone.covariance << number(4), number(6), number(6), number(5);
    // Some shared files list a cone twice. Two cones cannot stand in one place: keep the first, so that the
    // virtual car does not knock over (and count) one cone twice.
    const bool repeated = std::any_of(track.cones.begin(), track.cones.end(), [&](const TrackCone& c) {
      return (c.position - cone.position).squaredNorm() < 1e-4;
    });
    if (repeated) {
      ++track.duplicates_dropped;
      continue;
    }
    track.cones.push_back(cone);
  }
  if (!have_header) throw TrackError(origin + ": empty file, expected a header line");
  if (!have_start) throw TrackError(origin + ": no car_start row");
  if (track.cones.empty()) throw TrackError(origin + ": no cones");
  return track;
}

namespace {
// Fixed decimals; a value that rounds to zero is written without a minus sign.
void append_number(std::string& out, double v, int decimals = 4) {
  char buf[40];
  if (std::fabs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0.0;
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  out += buf;
}
}  // namespace

std::string format_track(const Track& track) {
  std::string out = "tag,x,y,direction,x_variance,y_variance,xy_covariance\n";
  auto row = [&](const char* tag, const Vec2& p, double direction) {
    out += tag;
    out += ',';
    append_number(out, p.x());
    out += ',';
    append_number(out, p.y());
    out += ',';
    append_number(out, direction, 6);
    out += ",0,0,0\n";
  };
  row("car_start", track.start.position(), track.start.yaw);
  for (const auto& c : track.cones) {
    switch (c.role) {
      case ConeRole::Left:
        row("blue", c.position, 0.0);
        break;
      case ConeRole::Right:
        row("yellow", c.position, 0.0);
        break;
      case ConeRole::Other:
        row("orange", c.position, 0.0);
        break;
      case ConeRole::Timing:
        row("big_orange", c.position, 0.0);
        break;
      default:
        throw std::invalid_argument("format_track: a cone without a role");
    }
  }
  return out;
}

Track load_track(const std::filesystem::path& path, const ColourConvention& convention) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw TrackError(path.string() + ": cannot open track file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return parse_track(ss.str(), path.string(), convention);
}

}  // namespace fsd
