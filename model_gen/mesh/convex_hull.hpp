// 3-D convex hull of a point set (quickhull), for URDF mesh collision geometry.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace mrqp::gen {

struct ConvexHull {
  // The hull's vertices only (a subset of the input points, each once, in order of first
  // appearance in the input).
  std::vector<Eigen::Vector3d> vertices;
  // Triangles indexing `vertices`, counter-clockwise seen from outside, i.e. the normal
  // (v1 - v0) x (v2 - v0) points out of the hull. The triangles form a closed 2-manifold
  // (every edge is shared by exactly two faces, V - E + F = 2). Coplanar hull facets are
  // returned as several triangles (a cube has 12).
  std::vector<std::array<int, 3>> faces;
};

// Convex hull of `points`: quickhull with exact orientation tests (floating-point filter,
// exact expansion arithmetic when it is inconclusive), so the result is a closed, exactly
// convex triangulated surface whatever the rounding. The result depends only on the input,
// not on the build (fixed-order arithmetic, no FMA contraction).
//
// `eps` is a distance tolerance relative to the size of the input: tol = eps * (largest
// side of the axis-aligned bounding box), clamped below to a few machine epsilons. A point
// within tol of the hull built so far is treated as inside and does not become a vertex,
// so every input point ends up inside the hull or within about tol of it. Every vertex is
// an extreme point: points on a hull facet or edge (e.g. a grid on a cube's faces) are
// never vertices. Near-degenerate input (points a few tol apart) may give a hull whose own
// hull drops a few more vertices; on well-separated points the hull is idempotent.
//
// Degenerate input never crashes and returns no faces:
//   - no finite points                 -> no vertices;
//   - all points within tol of one     -> that point (the first of them);
//   - all points within tol of a line  -> the two extreme points along it;
//   - all points within tol of a plane -> the extreme points of the planar convex polygon,
//                                         in cyclic order (collinear ones dropped).
// Non-finite points are ignored; exact duplicates are merged.
ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, double eps = 1e-9);

}  // namespace mrqp::gen
