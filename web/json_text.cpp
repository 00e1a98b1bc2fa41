#include "web/json_text.hpp"

namespace fsd::web {

JsonText parse_json_text(std::string_view text) {
  JsonText out;
  try {
    out.value = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::out_of_range& e) {
    // nlohmann's one out_of_range of parsing is 406, "number overflow parsing '<text>'".
    out.value = nlohmann::json::value_t::discarded;
    out.number_out_of_range = true;
    const std::string what = e.what();
    const auto quote = what.find('\'');
    const std::string number = quote == std::string::npos ? "a number" : what.substr(quote, 66);
    out.error = number + " is out of range (beyond ±1.8e308)";
  } catch (const nlohmann::json::exception&) {
    out.value = nlohmann::json::value_t::discarded;
    out.error = "malformed JSON";
  }
  return out;
}

}  // namespace fsd::web
