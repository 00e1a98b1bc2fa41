// Cost of one vehicle-model step (the simulator calls it at 200 Hz or faster). Run: build/bench/vehicle_bench
#include <benchmark/benchmark.h>

#include <cmath>

#include "drivers/sim/vehicle/vehicle_model.hpp"

namespace {

using fsd::sim::ActuatorCommand;
using fsd::sim::VehicleModel;
using fsd::sim::VehicleParams;

// Slalom at speed: the dynamic model with tyre forces on every step.
void BM_VehicleStepDynamic(benchmark::State& state) {
  VehicleModel car{VehicleParams{}};
  car.reset(fsd::Pose2{}, 12.0);
  ActuatorCommand cmd;
  cmd.drive_enabled = true;
  cmd.target_speed = 12.0;
  long i = 0;
  for (auto _ : state) {
    cmd.steering = 0.1 * std::sin(0.005 * static_cast<double>(i++));
    car.step(1.0 / 200.0, cmd);
    benchmark::DoNotOptimize(car.truth());
  }
  state.counters["sim_s_per_wall_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / 200.0, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VehicleStepDynamic);

// Walking pace: the kinematic model.
void BM_VehicleStepKinematic(benchmark::State& state) {
  VehicleModel car{VehicleParams{}};
  car.reset(fsd::Pose2{}, 1.0);
  ActuatorCommand cmd;
  cmd.drive_enabled = true;
  cmd.target_speed = 1.0;
  cmd.steering = 0.3;
  for (auto _ : state) {
    car.step(1.0 / 200.0, cmd);
    benchmark::DoNotOptimize(car.truth());
  }
}
BENCHMARK(BM_VehicleStepKinematic);

}  // namespace

BENCHMARK_MAIN();
