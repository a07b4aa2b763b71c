// A contact of the multi-robot problem (eq. 2–17): a surface given as points in a frame of one
// entity, touching either the fixed environment or a frame of another entity. One set of
// generator coefficients λ ≥ 0 describes the force on the surface entity; the other entity feels
// exactly the opposite force at the same point, so Newton's third law holds by construction
// (the reaction is never a variable of its own).
#pragma once

#include <Eigen/Core>

#include <array>

namespace mrqp::problem {

inline constexpr int kMaxContactPoints = 8;
inline constexpr int kMaxConeGenerators = 16;

/// A contact with every name resolved to an index: cheap to copy, no allocation.
struct ContactDesc {
  int entity = -1;        ///< the surface's entity
  int frame = -1;         ///< the surface's frame (points and normal are in its coordinates)
  int other_entity = -1;  ///< −1: the fixed environment
  int other_frame = -1;   ///< frame of other_entity carrying the reaction
  int npoints = 0;
  std::array<Eigen::Vector3d, kMaxContactPoints> points{};
  /// Direction of the force applied ON `entity` (frame coordinates, unit).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double friction = 0.7;  ///< Coulomb μ
  int generators = 4;     ///< edges of the linearised cone per point (3 … kMaxConeGenerators)

  int variables() const noexcept { return npoints * generators; }
  /// Rows of the no-slip constraint: 3 for a point contact, 6 for a surface.
  int rows() const noexcept { return npoints == 1 ? 3 : 6; }
};

/// Unit edge `k` of the linearised friction cone of axis n (unit) and coefficient μ: the cone
/// {f : ‖f − (f·n)n‖ ≤ μ f·n} is approximated from inside by the pyramid spanned by
/// (n + μ(cos θk t1 + sin θk t2)) / ‖·‖, θk = 2πk/K, with t1, t2 an orthonormal basis of n⊥.
Eigen::Vector3d coneGenerator(const Eigen::Vector3d& n, double mu, int k, int K) noexcept;

/// Checks a ContactDesc against its own rules (points 1…8, generators 3…16, μ > 0, finite values,
/// non-zero normal, and for a surface of ≥ 2 points: at least 3 not on one line). Returns nullptr
/// when valid, else a static message.
const char* validateContact(const ContactDesc& c) noexcept;

}  // namespace mrqp::problem
