#pragma once
// The virtual car's ground truth in the form of the dashboard's /truth/* channels (sim runs only). Kept apart
// from what the stack estimates, so the overlay shows the stack's error once perception and localization land.
#include <vector>

#include "web/channels.hpp"

namespace fsd::sim {
class VirtualCar;
class World;
struct VehicleTruth;
}  // namespace fsd::sim

namespace fsd {

web::TruthState truth_state(const sim::VirtualCar& car);
// The same from a truth frame's state (a replayed recording of a simulated run).
web::TruthState truth_state(const sim::VehicleTruth& truth, int cones_hit);
// The standing cones of a truth frame, upright (a recording does not say where fallen cones lie).
std::vector<web::TruthCone> truth_cones(const std::vector<Cone>& standing);
// Every cone of the world as the simulator has it: standing on the ground, or lying where it fell.
std::vector<web::TruthCone> truth_cones(const sim::World& world);

}  // namespace fsd
