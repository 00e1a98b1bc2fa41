#include "common/mcap/fsd_profile.hpp"

#include <charconv>

namespace fsd::mcap {

StringMap recording_metadata() { return {{std::string(kRecordingVersionKey), std::to_string(kRecordingVersion)}}; }

std::optional<std::string> recording_version_problem(const std::vector<Metadata>& metadata) {
  for (const auto& m : metadata) {
    if (m.name != kRecordingMetadata) continue;
    const auto it = m.metadata.find(std::string(kRecordingVersionKey));
    if (it == m.metadata.end()) continue;
    const std::string& v = it->second;
    long long version = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), version);
    if (ec != std::errc() || end != v.data() + v.size() || version < 1)
      return "recording version '" + v + "' (" + std::string(kRecordingVersionKey) + ") is not a positive number";
    if (version > kRecordingVersion)
      return "recording version " + v + " is newer than this fsd's (" + std::to_string(kRecordingVersion) +
             "): replay it with a newer fsd-daemon";
  }
  return std::nullopt;
}

}  // namespace fsd::mcap
