#pragma once
// A simulated run that cannot succeed is refused at the start (exit 2), not driven for minutes: the mission must
// fit the layout, judged with the stack's own fits on the whole track file. Trackdrive and autocross need both
// boundaries; the skid pad needs its two circles around the start; acceleration and the EBS test a straight
// lane ahead of it.
#include <optional>
#include <string>

#include "common/track.hpp"
#include "control/autopilot.hpp"

namespace fsd {

// Why `mission` cannot be driven on `track`, naming what is missing; nullopt when it can.
std::optional<std::string> layout_refusal(const Track& track, Mission mission, const AutopilotConfig& control);

}  // namespace fsd
