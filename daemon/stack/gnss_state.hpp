#pragma once
// The vehicle state from GNSS-INS alone (run.localization_source = gnss, and truth on the car; `fused` adds the
// wheel speeds through the fusion filter): pose from the rear-axle ENU position and the heading, body velocity from the
// ground speed and the course, yaw rate from ROT, steering from the VCU's measured wheel angle.
#include "common/types.hpp"

namespace fsd {

// Whether a sample can stand for the pose: a fix (any quality), a heading and an ENU origin to place it in.
bool gnss_pose_usable(const GnssSample& s, bool have_origin);

// Body-frame state at the sample's stamp. Without velocity in the epoch vx = vy = 0; without a yaw rate, 0.
VehicleState state_from_gnss(const GnssSample& s, double steering_measured);

}  // namespace fsd
