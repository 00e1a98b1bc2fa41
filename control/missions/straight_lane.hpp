#pragma once
// The acceleration lane's centre line, fitted to its cones. The rules make the lane straight: two parallel rows of
// cones. The fit must not trust every cone: a single ghost (a tyre or post the LiDAR stages took for a cone, seen
// without the camera) taken into a principal-axis fit tilted a lane by 3.2 degrees, which is 4 m off at the far
// end of the braking zone. So the rows are found by consensus (RANSAC over pairs of cones on one row, the other row
// the parallel offset most cones agree on), and only their cones enter the least-squares line.
#include <optional>
#include <vector>

#include "common/types.hpp"
#include "control/planning/path.hpp"

namespace fsd {

struct StraightLaneConfig {
  double row_tolerance = 0.3;  // m: a cone belongs to a row when its offset is within this of the row's line
  double min_width = 2.0;      // m between the rows (the rules' lane is 3 m at least; cones stand on its edges)
  double max_width = 8.0;      // m between the rows
  double reach = 8.0;          // m either side of the start heading where cones may belong to the lane
  double behind = 5.0;         // m behind the start pose where cones may belong to the lane
  double max_angle = 0.5;      // rad between the start heading and the lane (the car stands in the lane)
  int min_row_cones = 4;       // cones on each row before a lane is fitted
};

// The lane's centre line from the foot of `start` for `length` m, sampled every `ds`; nullopt until both rows have
// min_row_cones cones.
std::optional<Path> straight_from_cones(const std::vector<Cone>& cones, const Pose2& start, double length, double ds,
                                        const StraightLaneConfig& config = {});

}  // namespace fsd
