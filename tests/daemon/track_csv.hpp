#pragma once
// The rows of a shared track file (EUFS/FSDS CSV: tag,x,y,direction,...), read here independently of
// common/track so that tests compare the stack with the file itself, not with the project's own loader.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fsd::test {

struct TrackCsvRow {
  std::string tag;  // blue, yellow, orange, big_orange, car_start
  double x = 0, y = 0, direction = 0;
};

inline std::vector<TrackCsvRow> read_track_csv(const std::string& path) {
  std::vector<TrackCsvRow> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string tag, x, y, dir;
    std::getline(ss, tag, ',');
    std::getline(ss, x, ',');
    std::getline(ss, y, ',');
    std::getline(ss, dir, ',');
    if (tag.empty()) continue;
    rows.push_back({tag, std::stod(x), std::stod(y), std::stod(dir)});
  }
  return rows;
}

}  // namespace fsd::test
