// Test helpers over model_gen's convex hull; see hull_faces.hpp.
#include "hull_faces.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

#include "convex_hull.hpp"

namespace mrqp::testing {

namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

HullFaces hullFaces(const std::vector<Eigen::Vector3d>& points) {
  const gen::ConvexHull h = gen::convexHull(points);
  return HullFaces{h.vertices, h.faces};
}

double pointHullDistance(const HullFaces& h, const Eigen::Vector3d& x) {
  double best = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (const auto& f : h.faces) {
    const Eigen::Vector3d& a = h.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& b = h.vertices[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& c = h.vertices[static_cast<std::size_t>(f[2])];
    best = std::min(best, (x - closestOnTriangle(x, a, b, c)).norm());
    if ((b - a).cross(c - a).dot(x - a) > 0.0) inside = false;
  }
  return inside ? -best : best;
}

double hullVolume(const HullFaces& h) {
  double v = 0.0;
  for (const auto& f : h.faces) {
    v += h.vertices[static_cast<std::size_t>(f[0])].dot(
        h.vertices[static_cast<std::size_t>(f[1])].cross(h.vertices[static_cast<std::size_t>(f[2])]));
  }
  return v / 6.0;
}

}  // namespace mrqp::testing
