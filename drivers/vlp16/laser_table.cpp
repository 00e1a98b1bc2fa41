#include "drivers/vlp16/laser_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

namespace fsd {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::optional<double> parse_number(std::string_view s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

LaserTable LaserTable::from_specs(const std::array<Spec, kLasers>& specs) {
  LaserTable t;
  // Ring = rank of the elevation (ROS velodyne numbering); ties keep the laser order.
  std::array<std::size_t, kLasers> order{};
  for (std::size_t i = 0; i < kLasers; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return specs[a].elevation_deg < specs[b].elevation_deg; });
  for (std::size_t rank = 0; rank < kLasers; ++rank) t.lasers_[order[rank]].ring = static_cast<std::uint16_t>(rank);
  for (std::size_t i = 0; i < kLasers; ++i) {
    auto& l = t.lasers_[i];
    l.elevation = specs[i].elevation_deg * std::numbers::pi / 180.0;
    l.cos_elevation = std::cos(l.elevation);
    l.sin_elevation = std::sin(l.elevation);
    l.vertical_offset = specs[i].vertical_offset_m;
    l.firing_slot = static_cast<std::uint8_t>(specs[i].firing_slot);
  }
  return t;
}

LaserTable LaserTable::builtin() {
  std::array<Spec, kLasers> specs{};
  for (std::size_t i = 0; i < kLasers; ++i)
    specs[i] = {wire::vlp16::kLaserTable[i].elevation_deg, wire::vlp16::kLaserTable[i].vertical_offset_m,
                static_cast<int>(i)};
  return from_specs(specs);
}

LaserTable LaserTable::from_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw LaserTableError("laser table '" + file.string() + "': cannot open file");
  const auto fail = [&](int line, const std::string& what) {
    return LaserTableError("laser table '" + file.string() + "' line " + std::to_string(line) + ": " + what);
  };

  std::string line;
  int line_no = 1;
  if (!std::getline(in, line)) throw fail(1, "empty file");
  // Column index of each known field, from the header.
  int col_id = -1, col_angle = -1, col_offset = -1, col_slot = -1;
  const auto header = split_commas(line);
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto h = header[c];
    int* col = h == "laser_id"                   ? &col_id
               : h == "vert_angle_deg"           ? &col_angle
               : h == "vert_offset_correction_m" ? &col_offset
               : h == "firing_order_in_sequence" ? &col_slot
                                                 : nullptr;
    if (col) *col = static_cast<int>(c);
  }
  if (col_id < 0 || col_angle < 0 || col_offset < 0)
    throw fail(1, "header must name laser_id, vert_angle_deg and vert_offset_correction_m");

  std::array<Spec, kLasers> specs{};
  std::array<bool, kLasers> seen{};
  std::array<bool, kLasers> slot_used{};
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const auto cells = split_commas(line);
    if (cells.size() != header.size())
      throw fail(line_no,
                 "expected " + std::to_string(header.size()) + " columns, got " + std::to_string(cells.size()));
    const auto number = [&](int col, const char* name) {
      const auto v = parse_number(cells[static_cast<std::size_t>(col)]);
      if (!v)
        throw fail(line_no,
                   std::string(name) + " is not a number: '" + std::string(cells[static_cast<std::size_t>(col)]) + "'");
      return *v;
    };
    const double id = number(col_id, "laser_id");
    if (id != std::floor(id) || id < 0 || id >= static_cast<double>(kLasers))
      throw fail(line_no, "laser_id must be an integer 0..15");
    const auto laser = static_cast<std::size_t>(id);
    if (seen[laser]) throw fail(line_no, "laser_id " + std::to_string(laser) + " appears twice");
    seen[laser] = true;
    Spec s;
    s.elevation_deg = number(col_angle, "vert_angle_deg");
    if (std::abs(s.elevation_deg) > 90.0) throw fail(line_no, "vert_angle_deg outside [-90, 90]");
    s.vertical_offset_m = number(col_offset, "vert_offset_correction_m");
    if (std::abs(s.vertical_offset_m) > 0.5) throw fail(line_no, "vert_offset_correction_m outside [-0.5, 0.5]");
    s.firing_slot = static_cast<int>(laser);
    if (col_slot >= 0) {
      const double slot = number(col_slot, "firing_order_in_sequence");
      if (slot != std::floor(slot) || slot < 0 || slot >= static_cast<double>(kLasers))
        throw fail(line_no, "firing_order_in_sequence must be an integer 0..15");
      s.firing_slot = static_cast<int>(slot);
      if (slot_used[static_cast<std::size_t>(s.firing_slot)])
        throw fail(line_no, "firing_order_in_sequence " + std::to_string(s.firing_slot) + " used twice");
      slot_used[static_cast<std::size_t>(s.firing_slot)] = true;
    }
    specs[laser] = s;
    ++rows;
  }
  if (rows != kLasers) throw fail(line_no, "expected 16 lasers, found " + std::to_string(rows));
  return from_specs(specs);
}

LaserTable LaserTable::load(const std::string& path) { return path.empty() ? builtin() : from_csv(path); }

}  // namespace fsd
