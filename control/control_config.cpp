#include "control/control_config.hpp"

#include "common/car.hpp"

namespace fsd {

const ConfigSection<PlannerConfig>& planner_section() {
  using C = PlannerConfig;
  static const auto s =
      ConfigSection<C>("control.planner")
          .number("range", &C::range, 5, 60, "m", "Cones farther from the car are not planned through.")
          .number("behind", &C::behind, 0, 20, "m", "Cones farther behind the rear axle are ignored.")
          .integer("max_cones", &C::max_cones, 10, 1000, "", "Nearest cones kept per plan (bounds the work).")
          .number("merge_distance", &C::merge_distance, 0, 1, "m", "Cones closer than this are one cone.")
          .number("reference_wavelength", &C::reference_wavelength, 0, 20, "m",
                  "The walk's midline is smoothed over this before the path is optimized in its corridor.", true)
          .number("ds", &C::ds, 0.05, 2, "m", "Spacing of the straight paths the missions lay (lanes, run-outs).")
          .number("free_from", &C::free_from, 0, 5, "m",
                  "Clearance from the cones is asked from this far ahead of the car (it stands where it is).", true)
          .number("min_length", &C::min_length, 0.5, 50, "m", "A shorter clear path is a failed plan.")
          .number("end_speed", &C::end_speed, 0, 40, "m/s",
                  "Speed allowed at the end of the planned horizon (0: a stop within what is seen).", true)
          .number("time_budget", &C::time_budget, 0.001, 1, "s",
                  "A plan whose CPU time exceeds this is counted late (a warning in the log and /metrics); time "
                  "spent waiting for a core does not count.",
                  true);
  return s;
}

const ConfigSection<CorridorWalkConfig>& walk_section() {
  using C = CorridorWalkConfig;
  static const auto s =
      ConfigSection<C>("control.planner")
          .boolean("use_colours", &C::use_colours, "Use cone colours; false plans colour-blind from geometry.", true)
          .number("width_min", &C::width_min, 1, 10, "m", "Shortest edge the walk may cross.")
          .number("width_max", &C::width_max, 2, 15, "m", "Longest crossing edge unless its colours say left-right.")
          .number("crossing_max", &C::crossing_max, 2, 20, "m",
                  "Longest crossing edge between a left and a right cone.")
          .number("nominal_width", &C::nominal_width, 2, 10, "m", "Expected track width before the walk measured it.")
          .number("start_radius", &C::start_radius, 1, 20, "m", "First crossing within this distance ahead.")
          .number("start_angle_deg", &C::start_angle_deg, 10, 90, "deg", "First crossing within this bearing.")
          .number("max_turn_deg", &C::max_turn_deg, 10, 180, "deg", "Largest heading change between midpoints.")
          .number("min_crossing_cos", &C::min_crossing_cos, 0, 1, "",
                  "Crossing edge width across travel over its length, least.")
          .number("horizon", &C::horizon, 5, 100, "m", "Walks stop growing at this length.", true)
          .integer("beam_width", &C::beam_width, 1, 200, "", "Partial walks kept per step.")
          .integer("max_depth", &C::max_depth, 1, 500, "", "Steps per walk.")
          .number("w_turn", &C::w_turn, 0, 100, "1/rad²", "Cost of heading change.")
          .number("w_width", &C::w_width, 0, 100, "", "Cost of relative width change.")
          .number("w_unknown", &C::w_unknown, 0, 100, "", "Cost per crossed cone of unknown side.")
          .number("w_colour_conflict", &C::w_colour_conflict, 0, 100, "",
                  "Cost per cone whose colour says the other side.")
          .number("w_boundary_bend", &C::w_boundary_bend, 0, 100, "1/rad²",
                  "Cost of boundary bend beyond the free bend.")
          .number("boundary_free_bend_deg", &C::boundary_free_bend_deg, 0, 180, "deg",
                  "Boundary bend per cone that costs nothing.")
          .number("w_boundary_gap", &C::w_boundary_gap, 0, 100, "1/m²",
                  "Cost of boundary cone spacing beyond the maximum.")
          .number("boundary_spacing_max", &C::boundary_spacing_max, 1, 20, "m",
                  "Boundary cone spacing that costs nothing.")
          .number("w_length", &C::w_length, 0, 10, "1/m", "Reward per metre of walk.")
          .number("w_start", &C::w_start, 0, 10, "1/m", "Cost per metre from the car to the first midpoint.")
          .number("max_score", &C::max_score, -100, 100, "", "A best walk scoring worse is no plan.")
          .number("colour_check_margin", &C::colour_check_margin, -1, 100, "",
                  "A colour-blind walk this much better in geometry wins (< 0: off).")
          .integer("max_wrong_colours", &C::max_wrong_colours, 0, 20, "",
                   "... if it passes at most this many cones against their colour.")
          .number("fallback_below", &C::fallback_below, 0, 50, "m",
                  "Walks shorter than this, along them from the car, try the single-boundary fallback.");
  return s;
}

const ConfigSection<PathConfig>& path_section() {
  using C = PathConfig;
  static const auto s =
      ConfigSection<C>("control.path")
          .number("node_spacing", &C::node_spacing, 0.2, 2, "m",
                  "Spacing of the optimizer's nodes (the path: them, and the arc point half way between each two).")
          .number("cone_radius", &C::cone_radius, 0.05, 0.5, "m", "A small cone's base radius the body keeps from.")
          .number("big_cone_radius", &C::big_cone_radius, 0.05, 0.5, "m", "A big orange cone's base radius.")
          .number("accept_clearance", &C::accept_clearance, -0.1, 0.5, "m",
                  "A planned path whose body comes nearer a cone than this is cut before it (lap 1) or refused "
                  "(lap 2).",
                  true);
  return s;
}

const ConfigSection<PathOptimizerConfig>& optimizer_section() {
  using C = PathOptimizerConfig;
  static const auto s =
      ConfigSection<C>("control.path")
          .number("w_centre", &C::w_centre, 0, 1e3, "1/m³", "Cost per metre of the squared offset from the centre.",
                  true)
          .number("w_curvature", &C::w_curvature, 0, 1e4, "m", "Cost per metre of the squared curvature.", true)
          .number("w_curvature_rate", &C::w_curvature_rate, 0, 1e4, "m³",
                  "Cost per metre of the squared change of curvature along the path.", true)
          .number("lock_margin", &C::lock_margin, 0, 0.5, "",
                  "Share of the steering lock's curvature never planned (left to correct with).", true)
          .number("lock_margin_soft", &C::lock_margin_soft, 0, 0.5, "",
                  "Share below the lock's curvature where curvature starts to cost.", true)
          .number("w_lock_soft", &C::w_lock_soft, 0, 1e5, "m", "Cost per metre of curvature beyond that, squared.",
                  true)
          .number("kappa_rate_max", &C::kappa_rate_max, 0.01, 10, "1/m²", "Steepest change of curvature along a path.",
                  true)
          .number("clearance", &C::clearance, 0, 1, "m", "Kept between the body and every cone's base.", true)
          .number("clearance_soft", &C::clearance_soft, 0, 2, "m", "Below this, the clearance costs.", true)
          .number("w_clearance_soft", &C::w_clearance_soft, 0, 1e5, "1/m", "Cost per metre of that shortfall, squared.",
                  true)
          .number("penalty", &C::penalty, 1, 1e9, "", "Weight of a hard constraint's violation, squared.", true)
          .integer("max_iterations", &C::max_iterations, 1, 1000, "", "Solver iterations at most per plan.", true);
  return s;
}

const ConfigSection<ContactGuardConfig>& guard_section() {
  using C = ContactGuardConfig;
  static const auto s =
      ConfigSection<C>("control.guard")
          .boolean("enabled", &C::enabled, "Check the predicted motion against the mapped cones each cycle.", true)
          .number("horizon", &C::horizon, 0.1, 5, "s", "Predicted motion checked.", true)
          .number("dt", &C::dt, 0.01, 0.5, "s", "Step of the prediction.", true)
          .number("steer_rate", &C::steer_rate, 0.1, 10, "rad/s", "The steering actuator's rate, as predicted.", true)
          .number("steer_delay", &C::steer_delay, 0, 1, "s", "The steering actuator's dead time, as predicted.", true)
          .number("margin", &C::margin, -0.1, 1, "m", "A predicted clearance below this is a contact.", true)
          .number("decel", &C::decel, 0.5, 20, "m/s²",
                  "Braking the speed cap before a predicted contact assumes (and the prediction slows at).", true)
          .number("accel", &C::accel, 0.1, 20, "m/s²", "Acceleration the prediction speeds up at.", true)
          .number("latency", &C::latency, 0, 2, "s", "Delay before that braking acts, as assumed.", true)
          .number("range", &C::range, 2, 60, "m", "Cones farther from the car are not checked.", true);
  return s;
}

const ConfigSection<FollowerConfig>& follower_section() {
  using C = FollowerConfig;
  static const auto s =
      ConfigSection<C>("control.follower")
          .string("type", &C::type, {"pure_pursuit", "stanley", "lqr"}, "Path-following law.")
          .number("latency", &C::latency, 0, 1, "s", "Sensing-to-wheel delay the pose is predicted over.", true)
          .number("pp_gain", &C::pp_gain, 0, 5, "s", "Pure pursuit look-ahead per m/s (k in k·v + L0).", true)
          .number("pp_min", &C::pp_min, 0.5, 20, "m", "Pure pursuit look-ahead at standstill (L0).", true)
          .number("pp_max", &C::pp_max, 1, 50, "m", "Pure pursuit longest look-ahead.", true)
          .number("stanley_gain", &C::stanley_gain, 0, 50, "1/s", "Stanley cross-track gain k.", true)
          .number("stanley_softening", &C::stanley_softening, 0.01, 20, "m/s", "Stanley low-speed softening.", true)
          .number("lqr_q_lateral", &C::lqr_q_lateral, 0, 1e4, "1/m²", "LQR weight of lateral error.", true)
          .number("lqr_q_heading", &C::lqr_q_heading, 0, 1e4, "1/rad²", "LQR weight of heading error.", true)
          .number("lqr_r", &C::lqr_r, 1e-4, 1e4, "1/rad²", "LQR weight of steering.", true)
          .number("lqr_dt", &C::lqr_dt, 0.005, 0.5, "s", "LQR discretisation step.")
          .number("lqr_sideslip_gain", &C::lqr_sideslip_gain, 0, 0.1, "rad·s²/m",
                  "LQR: rear slip angle per lateral acceleration, taken off the heading error.", true)
          .number("lqr_preview", &C::lqr_preview, 0, 2, "s", "LQR curvature feed-forward taken this far ahead.", true)
          .number("speed_preview", &C::speed_preview, 0, 3, "s", "Target speed taken this far ahead on the path.", true)
          .number("speed_lead", &C::speed_lead, 0, 3, "s",
                  "Target speed leads by the path's acceleration times this (1 / VCU speed-loop gain).", true)
          .number("speed_lead_brake", &C::speed_lead_brake, 0, 3, "s", "The same lead where the path slows down.", true)
          .number("governor_offset", &C::governor_offset, 0, 5, "m",
                  "Farther off the path (or steering at its limit) the car does not speed up.", true)
          .number("governor_gain", &C::governor_gain, 0, 20, "m/s/m",
                  "... and slows by this per metre beyond the offset; 0 = off.", true)
          .number("governor_floor", &C::governor_floor, 0, 10, "m/s",
                  "... but never asks for less than this (a crawl back to the line).", true)
          .number("search_window", &C::search_window, 1, 100, "m", "Projection window around the last foot point.")
          .number("max_offset", &C::max_offset, 0.5, 20, "m", "Farther from the path is off path (stop).");
  return s;
}

const ConfigSection<SpeedConfig>& speed_section() {
  using C = SpeedConfig;
  static const auto s =
      ConfigSection<C>("control.speed")
          .number("mu", &C::mu, 0.1, 3, "", "Tyre-road friction coefficient of the car.", true)
          .number("mu_margin_realtime", &C::mu_margin_realtime, 0.1, 1, "",
                  "Share of mu when planning on what is seen.", true)
          .number("mu_margin_known", &C::mu_margin_known, 0.1, 1, "",
                  "Share of mu on a known straight (acceleration, EBS test).", true)
          .number("mu_margin_skidpad", &C::mu_margin_skidpad, 0.1, 1, "", "Share of mu on the skid pad.", true)
          .number("a_accel_max", &C::a_accel_max, 0.1, 30, "m/s²", "Traction acceleration limit.", true)
          .number("a_brake_max", &C::a_brake_max, 0.1, 30, "m/s²", "Service brake deceleration limit.", true)
          .number("power_max", &C::power_max, 0, 1e6, "W", "Power at the wheels; 0 = no power limit.")
          .number("v_max", &C::v_max, 0.5, 60, "m/s", "Target speed cap.", true)
          .number("v_max_realtime", &C::v_max_realtime, 0.5, 60, "m/s", "Cap when planning on what is seen (lap 1).",
                  true)
          .number("kappa_rate_max", &C::kappa_rate_max, 0, 10, "1/(m·s)",
                  "Fastest curvature change of the steering (rate / wheelbase); 0 = no limit.", true)
          .number("understeer", &C::understeer, 0, 0.1, "rad·s²/m",
                  "Understeer gradient K (δ = atan(L·κ) + K·v²·κ): each point is driven no faster than keeps the "
                  "steering within the lock less steer_reserve; 0 = no such limit.",
                  true)
          .number("steer_reserve", &C::steer_reserve, 0, 0.2, "rad",
                  "Steering left to correct with at every planned speed.", true)
          .number("stop_latency", &C::stop_latency, 0, 2, "s",
                  "From a stop being planned to the brakes acting: every stop is planned to hold with it.", true)
          .number("stop_margin", &C::stop_margin, 0, 10, "m",
                  "Every stop is planned this short of the end of the known free lane.", true)
          .boolean("traction_ellipse", &C::traction_ellipse,
                   "Traction shrinks with cornering on an ellipse (rear-wheel drive); false: friction circle capped at "
                   "a_accel_max.",
                   true);
  return s;
}

const ConfigSection<MissionConfig>& mission_section() {
  using C = MissionConfig;
  static const auto s =
      ConfigSection<C>("control.mission")
          .number("stop_decel", &C::stop_decel, 0.5, 15, "m/s²", "Braking to standstill after the finish.", true)
          .number("stop_distance", &C::stop_distance, 2, 200, "m", "Stop within this after the finish line.")
          .number("acceleration_length", &C::acceleration_length, 10, 500, "m",
                  "Acceleration: start line to finish line.")
          .number("acceleration_stop_distance", &C::acceleration_stop_distance, 5, 500, "m",
                  "Acceleration: stop within this after the finish.")
          .number("acceleration_stop_decel", &C::acceleration_stop_decel, 0.5, 15, "m/s²",
                  "Acceleration: braking to standstill after the finish (hard: a braking zone may be short).", true)
          .number("acceleration_start_offset", &C::acceleration_start_offset, 0, 50, "m",
                  "Start pose to start line when no timing cones are seen.")
          .number("open_end_sight", &C::open_end_sight, 0, 50, "m",
                  "Open layout: a plan ending this near with no cone beyond ends the track (0: off).")
          .number("open_end_min_travel", &C::open_end_min_travel, 0, 1000, "m",
                  "Open layout: driven this far before an end of the track is believed.")
          .number("open_end_settle", &C::open_end_settle, 0, 10, "s",
                  "Open layout: cone updates unbroken this long before an end of the track is believed (the map "
                  "refills after a sensor gap).")
          .number("open_end_confirm", &C::open_end_confirm, 0, 50, "m",
                  "An open layout's end is believed once it stayed in sight, with no cone beyond, on every fresh "
                  "plan over this distance driven (a plan that ends short for a moment is no end).")
          .number("ebs_trigger_distance", &C::ebs_trigger_distance, 1, 500, "m",
                  "EBS test: ask for Emergency this far past the start line.")
          .number("skidpad_exit_length", &C::skidpad_exit_length, 5, 100, "m", "Skid pad exit lane past the crossing.")
          .number("skidpad_entry_speed", &C::skidpad_entry_speed, 0.5, 20, "m/s",
                  "Skid pad speed until the circles are fitted.", true)
          .number("inspection_duration", &C::inspection_duration, 1, 600, "s", "Inspection steering sweep duration.")
          .number("inspection_speed", &C::inspection_speed, 0, 5, "m/s", "Inspection wheel speed.")
          .number("inspection_period", &C::inspection_period, 0.5, 30, "s", "Inspection sweep period.")
          .number("inspection_amplitude", &C::inspection_amplitude, 0, 1, "", "Share of the steering limit swept.");
  return s;
}

const ConfigSection<SupervisorConfig>& supervisor_section() {
  using C = SupervisorConfig;
  static const auto s =
      ConfigSection<C>("control.supervisor")
          .number("lidar_timeout", &C::lidar_timeout, 0.05, 10, "s", "No cone detections this long: slow down.")
          .number("camera_timeout", &C::camera_timeout, 0.05, 10, "s",
                  "No camera frame this long, once one came: a fault; the LiDAR stages detect alone.")
          .number("lidar_stop_timeout", &C::lidar_stop_timeout, 0.1, 30, "s",
                  "No cone detections this long: controlled stop.")
          .number("pose_timeout", &C::pose_timeout, 0.02, 5, "s", "No pose this long: controlled stop.")
          .number("vcu_timeout", &C::vcu_timeout, 0.02, 5, "s", "No VCU status this long: controlled stop.")
          .number("plan_timeout", &C::plan_timeout, 0.05, 10, "s", "No usable plan this long: controlled stop.")
          .number("degraded_speed", &C::degraded_speed, 0, 20, "m/s", "Speed cap while the LiDAR is stale.", true)
          .number("standstill_speed", &C::standstill_speed, 0.01, 2, "m/s", "Below this the car stands.")
          .number("standstill_time", &C::standstill_time, 0, 10, "s", "Standing this long counts as standstill.")
          .number("stop_timeout", &C::stop_timeout, 1, 60, "s",
                  "A controlled stop longer than this asks for Emergency.")
          .number("stuck_timeout", &C::stuck_timeout, 2, 600, "s",
                  "Standing this long in Driving before the finish (no way on): controlled stop.")
          .boolean("emergency_after_fault_stop", &C::emergency_after_fault_stop,
                   "Ask for Emergency at standstill after a fault stop.")
          .integer("max_faults", &C::max_faults, 1, 100000, "", "Faults kept in the log.");
  return s;
}

const ConfigSection<LapCounterConfig>& lap_counter_section() {
  using C = LapCounterConfig;
  static const auto s =
      ConfigSection<C>("control.laps")
          .number("hysteresis", &C::hysteresis, 1, 100, "m",
                  "Distance driven since the previous crossing before the next one counts.")
          .number("min_lap_time", &C::min_lap_time, 0, 600, "s", "Crossings closer in time are ignored.")
          .number("line_margin", &C::line_margin, 0, 10, "m", "The timing line's ends are extended by this.");
  return s;
}

const ConfigSection<RecordedTrajectoryConfig>& trajectory_section() {
  using C = RecordedTrajectoryConfig;
  static const auto s =
      ConfigSection<C>("control.trajectory")
          .number("sample_spacing", &C::sample_spacing, 0.05, 5, "m", "Spacing of recorded lap-1 poses.")
          .integer("max_samples", &C::max_samples, 100, 1000000, "", "Recorded poses kept at most.")
          .number("ds", &C::ds, 0.05, 2, "m", "Spacing of the lap path.")
          .number("smoothing_wavelength", &C::smoothing_wavelength, 0.5, 100, "m",
                  "Ripples of the driven line shorter than this are smoothed out.")
          .number("max_closure_gap", &C::max_closure_gap, 0.5, 50, "m",
                  "The lap must come back this close to its start.")
          .number("min_lap_length", &C::min_lap_length, 1, 10000, "m", "Shorter recorded laps are rejected.")
          .boolean("recentre", &C::recentre, "Pull the lap onto the middle of the mapped cones.")
          .number("recentre_reach", &C::recentre_reach, 0.5, 20, "m",
                  "Cones this close along and across count for recentring.")
          .string("line", &C::line, {"centre", "min_curvature"},
                  "Lap 2's line: near the centre line (control.path.w_centre), or the flattest within the mapped "
                  "boundaries.")
          .number("early_build_distance", &C::early_build_distance, 0, 50, "m",
                  "Lap 1's path is built and taken this far before the line (0: at the line).");
  return s;
}

const ConfigSection<Lap2Config>& lap2_section() {
  using C = Lap2Config;
  static const auto s =
      ConfigSection<C>("control.lap2")
          .number("mu_margin", &C::mu_margin, 0.1, 1, "", "Share of mu of the lap-2 speed profile (recorded line).",
                  true)
          .number("lqr_q_lateral", &C::lqr_q_lateral, 0, 1e4, "1/m²", "Lap-2 LQR weight of lateral error.", true)
          .number("lqr_q_heading", &C::lqr_q_heading, 0, 1e4, "1/rad²", "Lap-2 LQR weight of heading error.", true)
          .number("lqr_r", &C::lqr_r, 1e-4, 1e4, "1/rad²", "Lap-2 LQR weight of steering.", true)
          .number("speed_preview", &C::speed_preview, 0, 3, "s", "Lap 2: target speed taken this far ahead.", true)
          .number("speed_lead", &C::speed_lead, 0, 3, "s",
                  "Lap 2: target speed leads by the path's acceleration times this.", true)
          .number("speed_lead_brake", &C::speed_lead_brake, 0, 3, "s",
                  "Lap 2: the same lead where the path slows down.", true);
  return s;
}

const ConfigSection<AutopilotConfig>& autopilot_section() {
  using C = AutopilotConfig;
  static const auto s = ConfigSection<C>("control")
                            .number("replan_period", &C::replan_period, 0.01, 5, "s",
                                    "The real-time plan is refreshed at least this often.")
                            .number("gnss_timeout", &C::gnss_timeout, 0.05, 10, "s",
                                    "No good GNSS fix this long: lap 2 leaves the recorded lap for real-time planning, "
                                    "unless the pose was matched to the cone map within map_match_timeout.")
                            .number("map_match_timeout", &C::map_match_timeout, 0.05, 10, "s",
                                    "GNSS lost: lap 2 stays on the recorded lap while the pose was matched to the cone "
                                    "map this recently.");
  return s;
}

void describe_control(ConfigSchema& schema) {
  describe_car(schema);
  planner_section().describe(schema);
  walk_section().describe(schema);
  path_section().describe(schema);
  optimizer_section().describe(schema);
  guard_section().describe(schema);
  follower_section().describe(schema);
  speed_section().describe(schema);
  mission_section().describe(schema);
  supervisor_section().describe(schema);
  lap_counter_section().describe(schema);
  trajectory_section().describe(schema);
  lap2_section().describe(schema);
  autopilot_section().describe(schema);
}

namespace {
// The settings that more than one part reads, copied from the one place the configuration sets them.
void share_settings(AutopilotConfig& c) {
  c.trajectory.path = c.path;
  c.guard.understeer = c.speed.understeer;
  c.follower.understeer = c.speed.understeer;
}

// The car's description (car.*), read by every part that needs the car's size, steering or mass.
void describe_the_car(const CarDescription& car, AutopilotConfig& c) {
  c.follower.wheelbase = car.wheelbase;
  c.follower.max_steer = car.max_steer;
  c.speed.mass = car.mass;
  c.speed.wheelbase = car.wheelbase;
  c.speed.max_steer = car.max_steer;
  c.path.wheelbase = car.wheelbase;
  c.path.max_steer = car.max_steer;
  c.path.body = {car.nose(), car.rear_overhang, car.body_width / 2};
}
}  // namespace

AutopilotConfig read_control(const Config& config) {
  AutopilotConfig c = autopilot_section().read(config);
  c.planner = planner_section().read(config);
  c.planner.walk = walk_section().read(config);
  c.path = path_section().read(config);
  c.path.optimizer = optimizer_section().read(config);
  c.guard = guard_section().read(config);
  c.follower = follower_section().read(config);
  c.speed = speed_section().read(config);
  c.mission = mission_section().read(config);
  c.supervisor = supervisor_section().read(config);
  c.laps = lap_counter_section().read(config);
  c.trajectory = trajectory_section().read(config);
  c.lap2 = lap2_section().read(config);
  describe_the_car(read_car(config), c);
  share_settings(c);
  return c;
}

std::optional<double> control_param(const AutopilotConfig& c, const std::string& key) {
  for (auto v : {planner_section().value(key, c.planner), walk_section().value(key, c.planner.walk),
                 path_section().value(key, c.path), optimizer_section().value(key, c.path.optimizer),
                 guard_section().value(key, c.guard), follower_section().value(key, c.follower),
                 speed_section().value(key, c.speed), mission_section().value(key, c.mission),
                 supervisor_section().value(key, c.supervisor), lap_counter_section().value(key, c.laps),
                 trajectory_section().value(key, c.trajectory), lap2_section().value(key, c.lap2),
                 autopilot_section().value(key, c)})
    if (v) return v;
  return std::nullopt;
}

bool apply_control_param(AutopilotConfig& c, const std::string& key, double value) {
  const bool applied =
      planner_section().apply(key, value, c.planner) || walk_section().apply(key, value, c.planner.walk) ||
      path_section().apply(key, value, c.path) || optimizer_section().apply(key, value, c.path.optimizer) ||
      guard_section().apply(key, value, c.guard) || follower_section().apply(key, value, c.follower) ||
      speed_section().apply(key, value, c.speed) || mission_section().apply(key, value, c.mission) ||
      supervisor_section().apply(key, value, c.supervisor) || lap_counter_section().apply(key, value, c.laps) ||
      trajectory_section().apply(key, value, c.trajectory) || lap2_section().apply(key, value, c.lap2) ||
      autopilot_section().apply(key, value, c);
  if (applied) share_settings(c);
  return applied;
}

}  // namespace fsd
