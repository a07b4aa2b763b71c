// Test helpers: the triangulated convex hull of a point set (model_gen's quickhull) and the exact
// distance of a point to it (the smallest point–triangle distance over its faces, Ericson 5.1.5).
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace mrqp::testing {

struct HullFaces {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;  ///< outward (v1 − v0) × (v2 − v0)
};

HullFaces hullFaces(const std::vector<Eigen::Vector3d>& points);
/// Distance from `x` to the hull's surface, negative inside.
double pointHullDistance(const HullFaces& h, const Eigen::Vector3d& x);
/// Volume of the hull (divergence theorem over its faces).
double hullVolume(const HullFaces& h);

}  // namespace mrqp::testing
