// Distance and witness points between two placed convex shapes (docs/collision.md).
//
// Separated shapes: the GJK distance loop on the polytope cores (Gilbert, Johnson, Keerthi 1988;
// the closest point of each simplex by enumerating its faces) ends exactly, then the radii are
// taken off: d = ‖b − a‖ − r_A − r_B, n = (b − a)/‖b − a‖, witnesses a + r_A n and b − r_B n.
// Cores that overlap: libccd's MPR penetration (ccdMPRPenetration, allocation-free) of the whole
// shapes gives the depth and direction: d = −depth (approximate). libccd also answers the cheap
// question "closer than δ?" the way the design card describes: both shapes inflated by δ/2 in
// their support functions intersect (ccdMPRIntersect) exactly when their distance is below δ, and
// marginDistance() reads a distance as margins − MPR penetration depth (a lower bound: MPR's depth
// is measured along its portal's normal, not the minimum one, see docs/collision.md).
//
// Real-time: noexcept, no allocation (libccd's MPR works on a fixed simplex; its GJK/EPA, which
// allocates its polytope, is not used).
#pragma once

#include <Eigen/Core>

#include <array>

#include "collision/shape.hpp"

namespace mrqp::collision {

struct DistanceResult {
  double distance = 0.0;                              ///< signed: negative when penetrating
  Eigen::Vector3d a = Eigen::Vector3d::Zero();        ///< witness point on A (world)
  Eigen::Vector3d b = Eigen::Vector3d::Zero();        ///< witness point on B (world)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, from A towards B
  bool penetrating = false;                           ///< the cores overlap: libccd's MPR answered
  int iterations = 0;                                 ///< GJK iterations
  /// GJK's final simplex (separated results; size 0 when penetrating): the witnesses on the cores
  /// are Σ λ_i simplex_a[i] and Σ λ_i simplex_b[i], vertices of the cores (world). The distance's
  /// second derivative goes through it (distance_rate.hpp).
  int simplex_size = 0;
  std::array<Eigen::Vector3d, 3> simplex_a{}, simplex_b{};
  std::array<double, 3> simplex_lambda{};
};

/// Signed distance between A and B with witness points. False only when libccd's MPR fails on
/// overlapping cores (then `out` holds distance 0 and the centres' direction).
bool distance(const PlacedShape& A, const PlacedShape& B, DistanceResult* out) noexcept;

/// True when A and B are closer than `delta` (> 0): libccd's MPR on the shapes inflated by delta/2.
bool closerThan(const PlacedShape& A, const PlacedShape& B, double delta) noexcept;

/// The design card's reading: both shapes inflated by `margin`, distance = 2 margin − libccd's MPR
/// penetration depth, a lower bound of the true distance; +inf when the inflated shapes are apart
/// (distance ≥ 2 margin). Witnesses from MPR's contact position. Tests compare it with distance().
bool marginDistance(const PlacedShape& A, const PlacedShape& B, double margin, DistanceResult* out) noexcept;

}  // namespace mrqp::collision
