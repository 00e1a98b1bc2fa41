#pragma once
// The virtual car's ground truth in the form of the dashboard's /truth/* channels (sim runs only). Kept apart
// from what the stack estimates, so the overlay shows the stack's error once perception and localization land.
#include <vector>

#include "web/channels.hpp"

namespace fsd::sim {
class VirtualCar;
class World;
}  // namespace fsd::sim

namespace fsd {

web::TruthState truth_state(const sim::VirtualCar& car);
// Every cone of the world as the simulator has it: standing on the ground, or lying where it fell.
std::vector<web::TruthCone> truth_cones(const sim::World& world);

}  // namespace fsd
