#include "drivers/vlp16/frame_assembler.hpp"

#include <cmath>
#include <numbers>

namespace fsd {

FrameAssembler::FrameAssembler(double cut_deg, std::size_t max_points)
    : cut_deg_(std::fmod(cut_deg, 360.0)), max_points_(max_points == 0 ? 1 : max_points) {
  if (cut_deg_ < 0) cut_deg_ += 360.0;
  if (!(cut_deg_ >= 0.0 && cut_deg_ < 360.0)) cut_deg_ = 0.0;  // NaN or rounding to 360
}

void FrameAssembler::cut(const ScanHandler& emit) {
  if (current_.points.empty()) return;
  current_.seq = seq_++;
  Scan done = std::move(current_);
  current_ = Scan{};
  current_.points.reserve(done.points.size());
  emit(std::move(done));
}

void FrameAssembler::add(Stamp packet_start, std::span<const Vlp16Return> returns, const ScanHandler& emit) {
  constexpr double kDegToRad = std::numbers::pi / 180.0;
  for (const auto& r : returns) {
    double rel = r.azimuth_deg - cut_deg_;
    if (rel < 0) rel += 360.0;
    if (!have_prev_) {
      armed_ = rel >= 90.0;  // starting just past the cut: this frame is (nearly) whole, no cut for a while
      have_prev_ = true;
    } else if (armed_ && rel < prev_rel_) {
      cut(emit);
      armed_ = false;
    }
    if (rel >= 90.0 && rel <= 270.0) armed_ = true;
    prev_rel_ = rel;

    if (current_.points.size() >= max_points_) {
      ++forced_cuts_;
      cut(emit);
    }
    Point& p = current_.points.emplace_back();
    p.x = static_cast<float>(r.x);
    p.y = static_cast<float>(r.y);
    p.z = static_cast<float>(r.z);
    p.intensity = r.intensity;
    p.ring = r.ring;
    p.azimuth = static_cast<float>(r.azimuth_deg * kDegToRad);
    p.distance = static_cast<float>(r.distance_m);
    p.t = packet_start + r.firing_offset_us * 1e-6;
    if (current_.points.size() == 1) current_.stamp = p.t;
  }
}

void FrameAssembler::flush(const ScanHandler& emit) { cut(emit); }

}  // namespace fsd
