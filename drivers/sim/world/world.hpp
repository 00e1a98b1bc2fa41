#pragma once
// The virtual car's world: the track's cones as 3D bodies, the ground, and distractors outside the track, with a
// nearest-hit raycast for the sensor models and the cone hit/knock-over bookkeeping for the scorecard.
//
// Bodies are analytic shapes (cone_geometry.hpp) in a uniform grid (world_grid.hpp). Cones and upright
// distractors stand perpendicular to the (possibly sloped) ground plane. A cone the car's footprint touches is
// counted once and from then on lies on its side, tip pointing away from the car.
//
// raycast() is const and keeps no state: sensors may call it from several threads. update_hits() changes the
// world and must not run at the same time as a raycast.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/time.hpp"
#include "common/track.hpp"
#include "drivers/sim/world/cone_geometry.hpp"
#include "drivers/sim/world/distractors.hpp"
#include "drivers/sim/world/world_config.hpp"
#include "drivers/sim/world/world_grid.hpp"
#include "drivers/sim/world/world_ground.hpp"
#include "drivers/sim/world/world_track_area.hpp"

namespace fsd::sim {

const char* to_string(Surface s);

struct RayHit {
  double distance = 0;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // outward unit normal of the surface hit
  Surface surface = Surface::None;
  double reflectivity = 0;  // VLP-16 calibrated reflectivity of the material, 0..255
  int cone = -1;            // index into World::cones() when a cone was hit
  int distractor = -1;      // index into World::distractors() when a distractor was hit
};

// A laser beam's vertical footprint: `aperture` at the sensor, growing by `divergence` (rad, full angle) per metre.
// A beam that straddles a cone's stripe edge returns the mean of the two paints over its footprint, as a real
// sensor's does; the default is a point ray (the surface at the hit alone).
struct Beam {
  double aperture = 0.0;    // m
  double divergence = 0.0;  // rad
};

struct WorldCone {
  Vec3 base = Vec3::Zero();  // centre of the base on the ground, map frame
  ConeColour colour = ConeColour::Unknown;
  ConeRole role = ConeRole::Unknown;
  bool big = false;  // big orange (timing) cone
  double height = 0, base_width = 0;
  bool knocked = false;
  Stamp hit_time = 0;
  double fall_yaw = 0;  // direction the tip points once knocked
};

class World {
 public:
  World(const Track& track, const WorldConfig& cfg, std::uint64_t seed);

  const Track& track() const { return track_; }
  const WorldConfig& config() const { return cfg_; }
  const std::vector<WorldCone>& cones() const { return cones_; }
  const std::vector<Distractor>& distractors() const { return distractors_; }

  double ground_height(double x, double y) const { return ground_.height(x, y); }
  Vec3 ground_normal() const { return ground_.normal(); }
  // Rotation ground-aligned (z = ground normal) → map.
  const Eigen::Matrix3d& ground_frame() const { return ground_frame_; }
  // Map ← cone body frame (z along the cone's axis): upright on its base, or a knocked cone lying on its side with
  // the tip towards fall_yaw. One placement for the ray caster, the camera and the truth channel.
  Pose3 cone_pose(const WorldCone& c) const;
  Surface ground_surface(double x, double y) const { return ground_.surface(x, y); }
  double ground_reflectivity(double x, double y) const { return ground_.reflectivity(x, y); }
  // Distance from the nearest track boundary (both boundaries, joined cone to cone).
  double distance_to_track_boundary(const Vec2& p) const { return area_.distance_to_boundary(p); }
  bool on_track(const Vec2& p) const { return area_.on_track(p); }

  // Nearest hit along origin + t·unit_dir for 0 < t ≤ max_range, or nothing. `beam`: the footprint over which a
  // cone's paint is averaged (its reflectivity; the surface named is the one at the hit).
  std::optional<RayHit> raycast(const Vec3& origin, const Vec3& unit_dir, double max_range,
                                const Beam& beam = {}) const;

  // Marks the upright cones that the car footprint (polygon, map frame) touches as hit and knocks them over;
  // returns how many are newly hit.
  int update_hits(std::span<const Vec2> footprint, Stamp t);
  int cones_hit() const { return hits_; }

 private:
  struct Body {
    enum class Shape : std::uint8_t { Frustum, Panel };
    Shape shape = Shape::Frustum;
    Eigen::Matrix3d to_local = Eigen::Matrix3d::Identity();  // rotation map → body
    Vec3 origin = Vec3::Zero();                              // body origin in the map
    double a = 0, b = 0, h = 0;  // frustum: base radius, top radius, height; panel: length, unused, height
    Vec3 centre = Vec3::Zero();  // bounding sphere
    double bound_radius = 0;
    int cone = -1, distractor = -1;
  };

  // Bodies are indexed in two layers by height so that a ray walks a layer's grid only while it is low enough to
  // hit one of its bodies: the many small cones and lying tyres (below the LiDAR, so rays going up skip them at
  // once) in a fine grid, and the few taller objects (big cones, standing tyres, stacks, posts, fences) in a
  // coarse one. (A third layer costs more in per-ray setup than it saves.)
  struct Layer {
    UniformGrid grid;
    double max_height = 0;  // top of the tallest body above the ground
  };

  Body cone_body(int index) const;
  void add_distractor_bodies(int index);
  void finish_body(Body& body) const;
  Eigen::AlignedBox3d bounds(const Body& body) const;
  void rebuild_index();
  RayHit describe_hit(const Body& body, const LocalHit& hit, const Vec3& origin, const Vec3& dir,
                      const Beam& beam) const;

  Track track_;
  WorldConfig cfg_;
  TrackArea area_;
  Ground ground_;
  Eigen::Matrix3d ground_frame_;  // rotation: ground-aligned (z = ground normal) → map
  std::vector<WorldCone> cones_;
  std::vector<Distractor> distractors_;
  std::vector<Body> bodies_;  // cones first (body i is cone i), then distractors
  std::array<Layer, 2> layers_;
  int hits_ = 0;
};

}  // namespace fsd::sim
