// The car is described once (car.*): control, the drivers, perception, the dashboard and the virtual car read the
// same keys, and the virtual car departs from them only by sim.mismatch.*.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/car.hpp"
#include "control/control_config.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/gnss/gnss_config.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "drivers/vlp16/config.hpp"
#include "perception/lidar_cone_detector.hpp"

namespace fsd {
namespace {

Config configured(const char* json) {
  Config cfg(config_schema());
  cfg.merge(nlohmann::json::parse(json), "test");
  return cfg;
}

TEST(CarDescription, OneKeyMovesEveryPartThatReadsTheCar) {
  const Config cfg = configured(R"({"car": {"wheelbase": 1.6, "max_steer": 0.45, "mass": 250, "body_length": 3.0,
      "rear_overhang": 0.4, "body_width": 1.5, "lidar": {"x": 1.8, "z": 0.5, "yaw": 0.05},
      "gnss_antenna": {"x": 0.7, "z": 1.1}}})");

  const AutopilotConfig control = read_control(cfg);
  EXPECT_DOUBLE_EQ(control.follower.wheelbase, 1.6);
  EXPECT_DOUBLE_EQ(control.follower.max_steer, 0.45);
  EXPECT_DOUBLE_EQ(control.speed.mass, 250.0);
  EXPECT_DOUBLE_EQ(control.path.wheelbase, 1.6);
  EXPECT_DOUBLE_EQ(control.path.max_steer, 0.45);
  EXPECT_DOUBLE_EQ(control.path.body.front, 2.6);  // 3.0 long, 0.4 of it behind the rear axle
  EXPECT_DOUBLE_EQ(control.path.body.rear, 0.4);
  EXPECT_DOUBLE_EQ(control.path.body.half_width, 0.75);
  EXPECT_DOUBLE_EQ(control.trajectory.path.body.front, 2.6);
  EXPECT_DOUBLE_EQ(control.speed.wheelbase, 1.6);
  EXPECT_DOUBLE_EQ(control.speed.max_steer, 0.45);

  const Vlp16Config lidar = read_vlp16_config(cfg);
  EXPECT_DOUBLE_EQ(lidar.mount.x, 1.8);
  EXPECT_DOUBLE_EQ(lidar.mount.y, 0.0);
  EXPECT_DOUBLE_EQ(lidar.mount.z, 0.5);
  EXPECT_DOUBLE_EQ(lidar.mount.yaw, 0.05);
  const GnssConfig gnss = read_gnss_config(cfg);
  EXPECT_DOUBLE_EQ(gnss.antenna_x, 0.7);
  EXPECT_DOUBLE_EQ(gnss.antenna_z, 1.1);

  // The LiDAR's self-filter: the body grown by perception.lidar.roi.body_margin (0.1 m).
  const RoiConfig roi = read_lidar_detector_config(cfg).roi;
  EXPECT_DOUBLE_EQ(roi.body_x_min, -0.5);
  EXPECT_DOUBLE_EQ(roi.body_x_max, 2.7);
  EXPECT_DOUBLE_EQ(roi.body_y_min, -0.85);
  EXPECT_DOUBLE_EQ(roi.body_y_max, 0.85);

  const sim::VirtualCarSettings car = sim::read_virtual_car_settings(cfg);
  EXPECT_DOUBLE_EQ(car.vehicle.wheelbase, 1.6);
  EXPECT_DOUBLE_EQ(car.vehicle.steer_max_angle, 0.45);
  EXPECT_DOUBLE_EQ(car.vehicle.mass, 250.0);
  EXPECT_DOUBLE_EQ(car.vehicle.body_length, 3.0);
  EXPECT_DOUBLE_EQ(car.vehicle.rear_overhang, 0.4);
  EXPECT_DOUBLE_EQ(car.vehicle.body_width, 1.5);
  EXPECT_DOUBLE_EQ(car.lidar.x, 1.8);
  EXPECT_DOUBLE_EQ(car.lidar.z, 0.5);
  EXPECT_DOUBLE_EQ(car.lidar.yaw, 0.05);
  EXPECT_DOUBLE_EQ(car.gnss.antenna_x, 0.7);
  EXPECT_DOUBLE_EQ(car.gnss.antenna_z, 1.1);
}

TEST(CarDescription, TheDefaultsAreTheVirtualCarsAndEveryPartAgrees) {
  const Config cfg(config_schema());
  const CarDescription car = read_car(cfg);
  const sim::VirtualCarSettings sim_car = sim::read_virtual_car_settings(cfg);
  const AutopilotConfig control = read_control(cfg);
  EXPECT_EQ(sim_car.vehicle.wheelbase, control.follower.wheelbase);
  EXPECT_EQ(sim_car.vehicle.steer_max_angle, control.follower.max_steer);
  EXPECT_EQ(sim_car.vehicle.mass, control.speed.mass);
  EXPECT_EQ(sim_car.vehicle.body_length - sim_car.vehicle.rear_overhang, control.path.body.front);
  EXPECT_TRUE(sim::lidar_mount(sim_car.lidar).isApprox(read_vlp16_config(cfg).body_from_sensor()));
  EXPECT_EQ(sim_car.gnss.antenna_x, read_gnss_config(cfg).antenna_x);
  EXPECT_EQ(sim_car.gnss.antenna_z, read_gnss_config(cfg).antenna_z);
  EXPECT_DOUBLE_EQ(car.nose(), 2.4);
}

TEST(CarDescription, AMismatchMovesOnlyTheSimulatedCar) {
  const Config cfg = configured(R"({"sim": {"mismatch": {"wheelbase": 0.05, "mass": 30, "max_steer": -0.02,
      "lidar_x": 0.1, "lidar_pitch": 0.01, "antenna_y": 0.2}}})");
  const sim::VirtualCarSettings sim_car = sim::read_virtual_car_settings(cfg);
  EXPECT_DOUBLE_EQ(sim_car.vehicle.wheelbase, 1.58);
  EXPECT_DOUBLE_EQ(sim_car.vehicle.mass, 260.0);
  EXPECT_DOUBLE_EQ(sim_car.vehicle.steer_max_angle, 0.48);
  EXPECT_DOUBLE_EQ(sim_car.lidar.x, 2.1);
  EXPECT_DOUBLE_EQ(sim_car.lidar.pitch, 0.01);
  EXPECT_DOUBLE_EQ(sim_car.gnss.antenna_y, 0.2);
  // What the software believes stays the description.
  EXPECT_DOUBLE_EQ(read_control(cfg).follower.wheelbase, 1.53);
  EXPECT_DOUBLE_EQ(read_control(cfg).speed.mass, 230.0);
  EXPECT_DOUBLE_EQ(read_vlp16_config(cfg).mount.x, 2.0);
  EXPECT_DOUBLE_EQ(read_vlp16_config(cfg).mount.pitch, 0.0);
  EXPECT_DOUBLE_EQ(read_gnss_config(cfg).antenna_y, 0.0);
}

TEST(CarDescription, ThePerPartCopiesOfTheCarAreGone) {
  for (const char* json :
       {R"({"control": {"follower": {"wheelbase": 1.6}}})", R"({"control": {"speed": {"mass": 240}}})",
        R"({"control": {"path": {"body_front": 2.5}}})", R"({"drivers": {"vlp16": {"mount_x": 1.5}}})",
        R"({"drivers": {"gnss": {"antenna_x": 0.4}}})", R"({"sim": {"vehicle": {"wheelbase": 1.6}}})",
        R"({"sim": {"lidar": {"x": 1.5}}})", R"({"sim": {"gnss": {"antenna_z": 1.0}}})"}) {
    Config cfg(config_schema());
    EXPECT_THROW(cfg.merge(nlohmann::json::parse(json), "test"), ConfigError) << json;
  }
}

TEST(CarDescription, ANoseBehindTheFrontAxleIsRefusedWithTheKeys) {
  const Config cfg = configured(R"({"car": {"body_length": 1.9, "rear_overhang": 0.5}})");
  try {
    read_car(cfg);
    FAIL() << "a 1.4 m nose ahead of a 1.53 m wheelbase was accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("car.body_length"), std::string::npos) << what;
    EXPECT_NE(what.find("car.wheelbase"), std::string::npos) << what;
  }
}

TEST(CarDescription, EveryLibraryDeclaresTheCarAndTheSchemaHoldsItOnce) {
  ConfigSchema schema;
  describe_control(schema);
  sim::describe_virtual_car_config(schema);
  describe_lidar_detector_config(schema);
  int wheelbase_keys = 0;
  for (const auto& e : schema.entries()) wheelbase_keys += e.key == "car.wheelbase";
  EXPECT_EQ(wheelbase_keys, 1);
  EXPECT_NE(schema.find("car.lidar.yaw"), nullptr);
  EXPECT_NE(schema.find("car.gnss_antenna.z"), nullptr);
}

}  // namespace
}  // namespace fsd
