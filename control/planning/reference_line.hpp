#pragma once
// What the path optimizer works on (control/planning/path_optimizer.hpp): a reference line through the corridor as
// nodes every ds with their normals, and each node's room, how far along its normal the car's rear axle may move
// either way before half the body would stand over a boundary's cone line.
#include <vector>

#include "common/geometry.hpp"

namespace fsd {

struct ReferenceLine {
  std::vector<Vec2> nodes;
  std::vector<Vec2> normals;  // unit, to the left of the direction of travel
  bool closed = false;
  double ds = 0;
};

// Nodes every `ds` along `polyline` (closed: round to its start), smoothed so that ripples shorter than
// `wavelength` go (0: not smoothed), normals from the smoothed line. Empty for fewer than 2 points.
ReferenceLine make_reference(const std::vector<Vec2>& polyline, bool closed, double ds, double wavelength);

// Recomputes the normals from the nodes (after nodes were replaced).
void compute_normals(ReferenceLine& ref);

struct Room {
  std::vector<double> lo, hi;  // per node: the offset range along the normal, lo ≤ hi
};

// Room between two boundary polylines (cone lines, in order along the track; closed: round to their start): along
// each node's normal, the nearest crossing of the left line on its left and of the right line on its right, less
// `inset` (half the body and a cone). A side whose line is not crossed within `reach` gets `fallback` from the node.
// Where the two leave less than nothing, the node may only sit half way between them.
Room room_between(const ReferenceLine& ref, const std::vector<Vec2>& left, const std::vector<Vec2>& right,
                  bool boundaries_closed, double inset, double reach, double fallback);

// Where a line crosses each node's normal: the offset along it (the nearest crossing within `reach` either way), for
// starting the optimizer from a path planned before; nodes whose normal the line does not cross get 0.
std::vector<double> offsets_of(const ReferenceLine& ref, const std::vector<Vec2>& line, double reach);

}  // namespace fsd
