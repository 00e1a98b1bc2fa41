#include "localization/loop_closure/loop_closure_config.hpp"

namespace fsd::loop_closure {

namespace {

const ConfigSection<LoopCloserConfig>& closer_section() {
  using C = LoopCloserConfig;
  static const auto s =
      ConfigSection<C>("localization.loop_closure")
          .boolean("enabled", &C::enabled,
                   "run.localization_source = lidar_odometry closes each lap's loop on the start's cones: the pose, "
                   "the cone map and the recorded lap are corrected by the lap's solved pose graph.")
          .number("keyframe_spacing", &C::keyframe_spacing, 0.1, 20.0, "m", "Distance driven between keyframes.")
          .number("start_distance", &C::start_distance, 0.0, 100.0, "m",
                  "Cones first seen within this much driving from the start form the start's scene.")
          .number("min_lap_distance", &C::min_lap_distance, 10.0, 10000.0, "m",
                  "A lap's loop may close only after this much driving on it.")
          .number("near_start", &C::near_start, 1.0, 100.0, "m",
                  "The estimated pose this close to the start pose is back at the start.")
          .number("recent_distance", &C::recent_distance, 1.0, 100.0, "m",
                  "The scene now: the cones seen within the last this many metres driven.")
          .number("live_distance", &C::live_distance, 1.0, 1000.0, "m",
                  "A cone not seen for this much driving takes no more sightings (seen again: a new landmark).")
          .number("association_gate", &C::association_gate, 0.05, 5.0, "m",
                  "A sighting this close to a live landmark is that cone.")
          .number("max_range", &C::max_range, 1.0, 100.0, "m", "Sightings farther than this are left out.")
          .number("sighting_sigma", &C::sighting_sigma, 0.001, 5.0, "m", "σ per axis of a cone's sighting.")
          .integer("min_sightings", &C::min_sightings, 1, 100, "",
                   "A landmark seen fewer times is not part of a scene.");
  return s;
}

const ConfigSection<ConeAlignmentConfig>& alignment_section() {
  using C = ConeAlignmentConfig;
  static const auto s =
      ConfigSection<C>("localization.loop_closure.alignment", LoopCloserConfig{}.alignment)
          .number("max_drift", &C::max_drift, 0.1, 50.0, "m",
                  "A cone seen now may be this far from where it was mapped at the start (the lap's drift).")
          .number("max_rotation", &C::max_rotation, 0.001, 3.0, "rad", "The lap's heading drift at most.")
          .number("pair_tolerance", &C::pair_tolerance, 0.01, 5.0, "m",
                  "A cone seen now and a start cone this close after the alignment are one cone.")
          .integer("min_pairs", &C::min_pairs, 3, 1000, "", "Fewer cones of the start seen again: no loop.")
          .number("landing_radius", &C::landing_radius, 0.05, 10.0, "m",
                  "A cone seen now this close to a start cone after an alignment should pair with it.")
          .integer("max_unpaired", &C::max_unpaired, 0, 1000, "",
                   "An alignment is consistent when at most this many cones landed near a start cone unpaired. "
                   "The consistent one with most pairs is the loop, unless another consistent one elsewhere pairs "
                   "rival_min_pairs (ambiguous: no loop).")
          .number("copy_radius", &C::copy_radius, 0.0, 5.0, "m",
                  "A cone seen now that landed unpaired this close to a paired one of a compatible colour is a copy "
                  "of it (the lap mapped it twice) and does not make an alignment inconsistent.")
          .integer("rival_min_pairs", &C::rival_min_pairs, 2, 1000, "",
                   "A consistent alignment elsewhere with this many pairs makes the scene ambiguous.");
  return s;
}

const ConfigSection<LapGraphConfig>& graph_section() {
  using C = LapGraphConfig;
  static const auto s =
      ConfigSection<C>("localization.loop_closure.graph")
          .number("translation_sigma_per_m", &C::translation_sigma_per_m, 1e-5, 1.0, "",
                  "σ of the estimator's relative translation per metre driven ...")
          .number("translation_sigma_min", &C::translation_sigma_min, 1e-5, 10.0, "m", "... and at least this.")
          .number("yaw_sigma_per_m", &C::yaw_sigma_per_m, 1e-6, 1.0, "rad/m",
                  "σ of the estimator's relative heading per metre driven ...")
          .number("yaw_sigma_min", &C::yaw_sigma_min, 1e-6, 1.0, "rad", "... and at least this.")
          .number("observation_huber", &C::observation_huber, 0.01, 10.0, "m",
                  "Cone sightings off by more count linearly (a wrong association).")
          .integer("max_iterations", &C::max_iterations, 1, 1000, "", "Solver iterations at most.");
  return s;
}

}  // namespace

void describe_loop_closure_config(ConfigSchema& schema) {
  closer_section().describe(schema);
  alignment_section().describe(schema);
  graph_section().describe(schema);
}

LoopCloserConfig read_loop_closure_config(const Config& cfg) {
  LoopCloserConfig c = closer_section().read(cfg);
  c.alignment = alignment_section().read(cfg);
  c.graph = graph_section().read(cfg);
  return c;
}

}  // namespace fsd::loop_closure
