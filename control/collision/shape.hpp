// A convex collision shape fixed to a frame of an entity (docs/collision.md): a sphere, a capsule,
// a box or a convex hull, each the Minkowski sum of a polytope "core" (a point, a segment, a box,
// the hull's vertices) and a ball of radius `radius`:
//
//   sphere  core = {0}, radius r            capsule core = segment [−h e_z, h e_z], radius r
//   box     core = [−a, a] (half extents)   hull    core = conv(vertices), radius 0
//
// The shape's own frame sits at (R, p) in its frame's coordinates. The core's support function is
// what the distance routine (distance.hpp) and libccd query; the radius is added apart, so every
// core is a polytope and the GJK loop ends exactly. Plain data: a hull's vertices are owned by
// whoever built the shape (ShapeSet) and outlive it.
#pragma once

#include <Eigen/Core>

namespace mrqp::collision {

enum class ShapeKind { Sphere, Capsule, Box, Hull };

struct Shape {
  ShapeKind kind = ShapeKind::Sphere;
  double radius = 0.0;                             ///< sphere, capsule: the swept radius
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  ///< box: half extents; capsule: (0, 0, h)
  const Eigen::Vector3d* vertices = nullptr;       ///< hull: vertices in the shape frame
  int nvertices = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< a point inside the core (hull: centroid)
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();   ///< shape frame in the carrying frame
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  /// Radius of a ball about the shape frame's origin that holds the whole shape.
  double boundingRadius() const noexcept;
  /// Support point of the core (radius excluded) in the shape frame, for a direction in that frame.
  Eigen::Vector3d coreSupport(const Eigen::Vector3d& dir) const noexcept;
};

Shape makeSphere(double radius);
/// A capsule along the shape frame's z axis: the segment of length `length` swept by `radius`.
Shape makeCapsule(double radius, double length);
/// A box of full extents `size`, centred at the shape frame's origin.
Shape makeBox(const Eigen::Vector3d& size);
/// A convex hull of `n` vertices (kept by the caller).
Shape makeHull(const Eigen::Vector3d* vertices, int n);

/// A shape placed in the world: x_world = R x_shape + p.
struct PlacedShape {
  const Shape* shape = nullptr;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  /// World support point of the core for a world direction.
  Eigen::Vector3d coreSupport(const Eigen::Vector3d& dir) const noexcept {
    return R * shape->coreSupport(R.transpose() * dir) + p;
  }
};

/// The world placement of `s` when its carrying frame is at (Rf, pf).
inline PlacedShape place(const Shape& s, const Eigen::Matrix3d& Rf, const Eigen::Vector3d& pf) noexcept {
  PlacedShape out;
  out.shape = &s;
  out.R.noalias() = Rf * s.R;
  out.p.noalias() = Rf * s.p;
  out.p += pf;
  return out;
}

}  // namespace mrqp::collision
