#include "control/planning/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <unordered_map>

#include <opencv2/imgproc.hpp>

namespace fsd {

namespace {

std::uint64_t key_of(float x, float y) {
  std::uint32_t a = 0, b = 0;
  std::memcpy(&a, &x, sizeof a);
  std::memcpy(&b, &y, sizeof b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

}  // namespace

Triangulation delaunay(const std::vector<Vec2>& points) {
  Triangulation out;
  if (points.size() < 3) return out;
  double minx = points[0].x(), miny = points[0].y(), maxx = minx, maxy = miny;
  for (const auto& p : points) {
    if (!p.allFinite()) return out;
    minx = std::min(minx, p.x());
    maxx = std::max(maxx, p.x());
    miny = std::min(miny, p.y());
    maxy = std::max(maxy, p.y());
  }
  // Subdiv2D wants an integer rectangle holding every point: shift into it with a margin; local float
  // coordinates keep sub-millimetre precision over a planning window.
  const double margin = 2.0;
  const double ox = std::floor(minx) - margin, oy = std::floor(miny) - margin;
  const int w = static_cast<int>(std::ceil(maxx - ox + margin)) + 1;
  const int h = static_cast<int>(std::ceil(maxy - oy + margin)) + 1;
  if (w <= 0 || h <= 0 || w > 1000000 || h > 1000000) return out;

  std::unordered_map<std::uint64_t, int> index;
  std::vector<cv::Point2f> local;
  local.reserve(points.size());
  try {
    cv::Subdiv2D subdiv(cv::Rect(0, 0, w, h));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const cv::Point2f q(static_cast<float>(points[i].x() - ox), static_cast<float>(points[i].y() - oy));
      const auto k = key_of(q.x, q.y);
      if (index.count(k)) continue;
      bool near_duplicate = false;
      for (const auto& l : local)
        if (std::abs(l.x - q.x) < 1e-3f && std::abs(l.y - q.y) < 1e-3f) near_duplicate = true;
      if (near_duplicate) continue;
      index.emplace(k, static_cast<int>(i));
      local.push_back(q);
      subdiv.insert(q);
    }
    std::vector<cv::Vec6f> tris;
    subdiv.getTriangleList(tris);
    std::map<std::pair<int, int>, int> edge_of;
    for (const auto& t : tris) {
      std::array<int, 3> v{};
      bool ok = true;
      for (int k = 0; k < 3 && ok; ++k) {
        const auto it = index.find(key_of(t[2 * k], t[2 * k + 1]));
        ok = it != index.end();
        if (ok) v[static_cast<std::size_t>(k)] = it->second;
      }
      if (!ok) continue;  // a triangle of Subdiv2D's virtual outer vertices
      const Vec2 a = points[static_cast<std::size_t>(v[0])], b = points[static_cast<std::size_t>(v[1])],
                 c = points[static_cast<std::size_t>(v[2])];
      const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (std::abs(area2) < 1e-9) continue;
      if (area2 < 0) std::swap(v[1], v[2]);
      const int ti = static_cast<int>(out.triangles.size());
      out.triangles.push_back(v);
      std::array<int, 3> te{};
      for (int k = 0; k < 3; ++k) {
        int p = v[static_cast<std::size_t>(k)], q = v[static_cast<std::size_t>((k + 1) % 3)];
        if (p > q) std::swap(p, q);
        auto [it, inserted] = edge_of.emplace(std::make_pair(p, q), static_cast<int>(out.edges.size()));
        if (inserted) {
          Triangulation::Edge e;
          e.a = p;
          e.b = q;
          e.tri[0] = ti;
          out.edges.push_back(e);
        } else {
          out.edges[static_cast<std::size_t>(it->second)].tri[1] = ti;
        }
        te[static_cast<std::size_t>(k)] = it->second;
      }
      out.triangle_edges.push_back(te);
    }
  } catch (const cv::Exception&) {
    return {};
  }
  return out;
}

}  // namespace fsd
