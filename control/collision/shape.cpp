// Convex collision shapes: construction, bounding radius and core support functions; see shape.hpp.
#include "collision/shape.hpp"

#include <algorithm>
#include <cmath>

namespace mrqp::collision {

double Shape::boundingRadius() const noexcept {
  switch (kind) {
    case ShapeKind::Sphere:
      return radius;
    case ShapeKind::Capsule:
      return half.z() + radius;
    case ShapeKind::Box:
      return half.norm();
    case ShapeKind::Hull: {
      double r = 0.0;
      for (int i = 0; i < nvertices; ++i) r = std::max(r, vertices[i].norm());
      return r;
    }
  }
  return 0.0;
}

Eigen::Vector3d Shape::coreSupport(const Eigen::Vector3d& d) const noexcept {
  switch (kind) {
    case ShapeKind::Sphere:
      return Eigen::Vector3d::Zero();
    case ShapeKind::Capsule:
      return Eigen::Vector3d(0.0, 0.0, d.z() >= 0.0 ? half.z() : -half.z());
    case ShapeKind::Box:
      return Eigen::Vector3d(d.x() >= 0.0 ? half.x() : -half.x(), d.y() >= 0.0 ? half.y() : -half.y(),
                             d.z() >= 0.0 ? half.z() : -half.z());
    case ShapeKind::Hull: {
      int best = 0;
      double h = vertices[0].dot(d);
      for (int i = 1; i < nvertices; ++i) {
        const double hi = vertices[i].dot(d);
        if (hi > h) {
          h = hi;
          best = i;
        }
      }
      return vertices[best];
    }
  }
  return Eigen::Vector3d::Zero();
}

Shape makeSphere(double radius) {
  Shape s;
  s.kind = ShapeKind::Sphere;
  s.radius = radius;
  return s;
}

Shape makeCapsule(double radius, double length) {
  Shape s;
  s.kind = ShapeKind::Capsule;
  s.radius = radius;
  s.half = Eigen::Vector3d(0.0, 0.0, 0.5 * length);
  return s;
}

Shape makeBox(const Eigen::Vector3d& size) {
  Shape s;
  s.kind = ShapeKind::Box;
  s.half = 0.5 * size;
  return s;
}

Shape makeHull(const Eigen::Vector3d* vertices, int n) {
  Shape s;
  s.kind = ShapeKind::Hull;
  s.vertices = vertices;
  s.nvertices = n;
  for (int i = 0; i < n; ++i) s.centre += vertices[i];
  if (n > 0) s.centre /= static_cast<double>(n);
  return s;
}

}  // namespace mrqp::collision
