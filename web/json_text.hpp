#pragma once
// Parsing a client's JSON text (an HTTP body, a WebSocket message) so that a number too large for a double
// (`1e999`) is told apart from malformed JSON: the client then learns that the number is out of range.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fsd::web {

struct JsonText {
  nlohmann::json value;  // discarded when the text did not parse
  std::string error;     // why not, empty when it parsed
  bool number_out_of_range = false;
};
JsonText parse_json_text(std::string_view text);

}  // namespace fsd::web
