#pragma once
// What `fsd mcap info` and `fsd mcap recover` print: the text a person reads and, for info, the JSON a script
// reads. Pure formatting of common/mcap's FileInfo and RecoverReport.
#include <string>

#include <nlohmann/json.hpp>

#include "common/mcap/inspect.hpp"
#include "common/mcap/recover.hpp"

namespace fsd {

std::string format_mcap_info(const std::string& file, const mcap::FileInfo& info);
nlohmann::json mcap_info_json(const std::string& file, const mcap::FileInfo& info);
std::string format_recover_report(const std::string& in, const std::string& out, const mcap::RecoverReport& r);

}  // namespace fsd
