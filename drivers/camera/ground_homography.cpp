#include "drivers/camera/ground_homography.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

namespace fsd {

namespace {
double parse_number(const std::string& s, const std::string& what) {
  std::size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  const std::string t = b == std::string::npos ? "" : s.substr(b, e - b + 1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
    throw HomographyError(what + ": '" + t + "' is not a number");
  return v;
}
}  // namespace

PointQuad parse_point_quad(const std::string& text, const std::string& what) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ';');) parts.push_back(item);
  if (!text.empty() && text.back() == ';') parts.push_back("");
  if (parts.size() != 4)
    throw HomographyError(what + ": expected 4 points 'a,b;a,b;a,b;a,b', got " + std::to_string(parts.size()));
  PointQuad q;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto comma = parts[i].find(',');
    if (comma == std::string::npos || parts[i].find(',', comma + 1) != std::string::npos)
      throw HomographyError(what + ": point " + std::to_string(i + 1) + " '" + parts[i] +
                            "' is not two numbers separated by a comma");
    const std::string label = what + " point " + std::to_string(i + 1);
    q[i] = Vec2(parse_number(parts[i].substr(0, comma), label), parse_number(parts[i].substr(comma + 1), label));
  }
  return q;
}

}  // namespace fsd
