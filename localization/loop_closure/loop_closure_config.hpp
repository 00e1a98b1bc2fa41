#pragma once
// localization.loop_closure.*: the LoopCloser's settings (its own, .alignment and .graph), in the daemon's schema.
#include "common/config.hpp"
#include "localization/loop_closure/loop_closer.hpp"

namespace fsd::loop_closure {

void describe_loop_closure_config(ConfigSchema& schema);
LoopCloserConfig read_loop_closure_config(const Config& cfg);

}  // namespace fsd::loop_closure
