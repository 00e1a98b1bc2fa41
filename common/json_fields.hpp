#pragma once
// Strict reading of one JSON object of an untrusted file (a calibration, a classifier model): every field checked
// for presence, type and range, unknown fields rejected, and every problem reported as
// "<origin>: field '<dotted.name>': <problem>" in the caller's exception type.
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fsd {

template <class Error>
class JsonFields {
 public:
  using json = nlohmann::json;

  JsonFields(const json& j, std::string origin, std::string path)
      : j_(j), origin_(std::move(origin)), path_(std::move(path)) {
    if (!j_.is_object()) fail("", "expected an object, got " + std::string(j_.type_name()));
  }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    const std::string full = field.empty() ? path_ : name(field);
    throw Error(origin_ + ": " + (full.empty() ? "" : "field '" + full + "': ") + problem);
  }

  bool has(const std::string& field) const { return j_.contains(field); }
  const json& at(const std::string& field) const {
    if (!j_.contains(field)) fail(field, "missing");
    return j_.at(field);
  }
  JsonFields object(const std::string& field) const { return {at(field), origin_, name(field)}; }
  void only(const std::set<std::string>& known) const {
    for (const auto& [key, value] : j_.items())
      if (!known.contains(key)) fail(key, "unknown field");
  }

  double number(const std::string& field, double lo, double hi) const { return number_in(at(field), field, lo, hi); }
  int integer(const std::string& field, int lo, int hi) const { return integer_in(at(field), field, lo, hi); }
  std::string string(const std::string& field) const {
    const json& v = at(field);
    if (!v.is_string()) fail(field, "expected a string, got " + v.dump());
    return v.get<std::string>();
  }
  // `v` is the array (a field or an element of one), `field` its name in messages.
  std::vector<double> numbers(const std::string& field, const json& v, double lo = -HUGE_VAL,
                              double hi = HUGE_VAL) const {
    if (!v.is_array()) fail(field, "expected an array of numbers, got " + v.dump());
    std::vector<double> out;
    out.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(number_in(v[i], field + "[" + std::to_string(i) + "]", lo, hi));
    return out;
  }
  std::vector<int> integers(const std::string& field, const json& v, int lo, int hi) const {
    if (!v.is_array()) fail(field, "expected an array of integers, got " + v.dump());
    std::vector<int> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(integer_in(v[i], field + "[" + std::to_string(i) + "]", lo, hi));
    return out;
  }
  std::string name(const std::string& field) const { return path_.empty() ? field : path_ + "." + field; }

 private:
  double number_in(const json& v, const std::string& field, double lo, double hi) const {
    if (!v.is_number()) fail(field, "expected a number, got " + v.dump());
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "not a finite number");
    if (d < lo || d > hi)
      fail(field, std::to_string(d) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return d;
  }
  int integer_in(const json& v, const std::string& field, int lo, int hi) const {
    if (!v.is_number_integer()) fail(field, "expected an integer, got " + v.dump());
    const auto i = v.get<long long>();
    if (i < lo || i > hi)
      fail(field, std::to_string(i) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(i);
  }

  const json& j_;
  std::string origin_;
  std::string path_;
};

}  // namespace fsd
