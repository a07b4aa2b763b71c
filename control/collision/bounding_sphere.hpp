// The cheap first test of a collision pair (docs/collision.md): each shape's bounding ball about its
// frame origin; a pair whose balls are farther apart than δi cannot be closer than δi.
#pragma once

#include "collision/shape.hpp"

namespace mrqp::collision {

/// Lower bound of the distance between A and B from their bounding balls (may be negative).
inline double boundingDistance(const PlacedShape& A, double radius_a, const PlacedShape& B,
                               double radius_b) noexcept {
  return (B.p - A.p).norm() - radius_a - radius_b;
}

}  // namespace mrqp::collision
