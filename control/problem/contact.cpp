#include "problem/contact.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace mrqp::problem {

Eigen::Matrix3d contactFrame(const Eigen::Vector3d& n) noexcept {
  // Any unit vector not parallel to n gives t1; t2 completes the right-handed basis.
  const Eigen::Vector3d seed = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix3d F;
  F.col(0) = (seed - seed.dot(n) * n).normalized();
  F.col(1) = n.cross(F.col(0));
  F.col(2) = n;
  return F;
}

Eigen::Vector3d coneGenerator(const Eigen::Vector3d& n, double mu, int k, int K) noexcept {
  const Eigen::Matrix3d F = contactFrame(n);
  const Eigen::Vector3d t1 = F.col(0);
  const Eigen::Vector3d t2 = F.col(1);
  const double th = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(K);
  return (n + mu * (std::cos(th) * t1 + std::sin(th) * t2)).normalized();
}

const char* validateContact(const ContactDesc& c) noexcept {
  if (c.entity < 0 || c.frame < 0) return "the surface's entity or frame is not set";
  if (c.other_entity >= 0 && c.other_frame < 0) return "the other entity's frame is not set";
  if (c.other_entity == c.entity) return "a contact needs two different entities";
  if (c.npoints < 1 || c.npoints > kMaxContactPoints) return "a contact has 1 to 8 points";
  if (c.generators < 3 || c.generators > kMaxConeGenerators) return "generators must be 3 to 16";
  if (!(c.friction > 0.0) || !std::isfinite(c.friction)) return "friction must be > 0";
  if (!c.normal.allFinite() || c.normal.norm() < 1e-9) return "the normal must be a non-zero vector";
  if ((c.free & ~kFreeAll) != 0) return "free directions are 6 bits: translations then rotations";
  if (c.npoints == 1 && (c.free & kFreeRotations) != 0) {
    return "a point contact holds no rotation: only its translations can be free";
  }
  for (int i = 0; i < c.npoints; ++i) {
    if (!c.points[static_cast<std::size_t>(i)].allFinite()) return "a point is not finite";
  }
  if (c.npoints >= 2) {
    // A surface contact constrains all 6 relative directions: it needs an area, not a line.
    const Eigen::Vector3d& p0 = c.points[0];
    double best = 0.0, scale = 0.0;
    for (int i = 1; i < c.npoints; ++i) {
      scale = std::max(scale, (c.points[static_cast<std::size_t>(i)] - p0).norm());
      for (int j = i + 1; j < c.npoints; ++j) {
        best = std::max(best, (c.points[static_cast<std::size_t>(i)] - p0)
                                  .cross(c.points[static_cast<std::size_t>(j)] - p0)
                                  .norm());
      }
    }
    if (scale <= 0.0 || best <= 1e-9 * scale * scale + 1e-12) {
      return "a surface contact needs at least 3 points not on one line (or give a single point)";
    }
  }
  return nullptr;
}

}  // namespace mrqp::problem
