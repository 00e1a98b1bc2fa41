#pragma once
// Delaunay triangulation of cone positions (OpenCV Subdiv2D) as plain index lists: triangles, their edges, and
// for each edge the one or two triangles beside it. The midline planner walks from triangle to triangle.
#include <array>
#include <vector>

#include "common/geometry.hpp"

namespace fsd {

struct Triangulation {
  struct Edge {
    int a = -1, b = -1;              // vertex indices, a < b
    std::array<int, 2> tri{-1, -1};  // adjacent triangles; tri[1] = -1 on the hull
    int other(int t) const { return tri[0] == t ? tri[1] : tri[0]; }
  };
  std::vector<std::array<int, 3>> triangles;       // vertex indices, counter-clockwise
  std::vector<std::array<int, 3>> triangle_edges;  // edge indices of each triangle
  std::vector<Edge> edges;
};

// Triangulates `points`; duplicates (closer than 1 mm) keep only their first copy. Fewer than 3 points, or all
// on one line, give no triangles.
Triangulation delaunay(const std::vector<Vec2>& points);

}  // namespace fsd
