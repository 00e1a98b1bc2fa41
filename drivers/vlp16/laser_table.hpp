#pragma once
// The per-laser calibration of a VLP-16: elevation, vertical offset, firing slot and ring. Built in from the
// manual (common/wire/vlp16_format.hpp) or loaded from a CSV file.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "common/wire/vlp16_format.hpp"

namespace fsd {

class LaserTableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LaserCalibration {
  double elevation = 0;  // rad, positive up
  double cos_elevation = 1, sin_elevation = 0;
  double vertical_offset = 0;    // m, added to z
  std::uint8_t firing_slot = 0;  // position in the firing sequence: fires at slot × 2.304 µs
  std::uint16_t ring = 0;        // rank of the elevation, 0 = lowest beam
};

class LaserTable {
 public:
  static constexpr std::size_t kLasers = wire::vlp16::kLasers;

  // The VLP-16 manual's table (identical to ../shared/data/vlp16/vlp16_lasers.csv).
  static LaserTable builtin();
  // Header `laser_id,vert_angle_deg,vert_offset_correction_m[,firing_order_in_sequence]` (any column order)
  // and one row per laser 0..15. Throws LaserTableError naming the file and line on any problem.
  static LaserTable from_csv(const std::filesystem::path& file);
  // "" = builtin(), else from_csv(path).
  static LaserTable load(const std::string& path);

  const LaserCalibration& operator[](std::size_t laser) const { return lasers_[laser]; }

 private:
  struct Spec {
    double elevation_deg = 0, vertical_offset_m = 0;
    int firing_slot = 0;
  };
  static LaserTable from_specs(const std::array<Spec, kLasers>& specs);
  std::array<LaserCalibration, kLasers> lasers_{};
};

}  // namespace fsd
