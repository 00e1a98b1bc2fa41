#pragma once
// service.recordings_dir: the folder every run records to, held under service.recordings_max_mb by deleting its
// oldest recordings (*.mcap, by modification time) at the start and at the end of each run.
#include <cstdint>
#include <string>

#include "daemon/service/service_settings.hpp"

namespace fsd {

// The path of this run's recording in the folder (created if missing): fsd-YYYYmmdd-HHMMSS.mcap, local time.
// Throws std::invalid_argument naming service.recordings_dir when the folder cannot be made.
std::string next_recording_path(const ServiceSettings& s);

// Deletes the oldest .mcap files of the folder until the rest total at most the cap; returns how many went.
// `keep`: a file never deleted (the recording being written).
int prune_recordings(const ServiceSettings& s, const std::string& keep = {});

}  // namespace fsd
