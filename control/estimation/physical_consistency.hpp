// Physical consistency of one body's inertial parameters φ = (m, h, I about the origin): a mass
// above a floor, a centre of mass inside a box (the object's geometry, optional), and a rotational
// inertia about the centre of mass that a real mass distribution can have — positive definite and
// satisfying the triangle inequalities Jᵢ + Jⱼ ≥ Jₖ of its principal moments.
//
// Both inertia conditions hold exactly when the second-moment matrix of the distribution,
// Σ = ½ tr(I_c) 1 − I_c, is positive semi-definite (I_c = tr(Σ) 1 − Σ maps principal second
// moments sᵢ ≥ 0 to principal moments Jᵢ = sⱼ + sₖ). The projection clamps Σ's eigenvalues from
// below (the nearest PSD matrix in the Frobenius norm of Σ) and maps back.
#pragma once

#include <Eigen/Core>

#include "estimation/rigid_body_regressor.hpp"

namespace mrqp::estimation {

struct ConsistencyBounds {
  double min_mass = 1e-3;           ///< kg
  double min_second_moment = 1e-9;  ///< kg·m², floor of Σ's eigenvalues (strict PD of I_c)
  bool bound_com = false;           ///< keep the CoM inside [com_lower, com_upper] (body frame)
  Eigen::Vector3d com_lower = Eigen::Vector3d::Constant(-1.0);
  Eigen::Vector3d com_upper = Eigen::Vector3d::Constant(1.0);
};

/// Whether φ is consistent within `tolerance` (mass ≥ min_mass, Σ ⪰ −tolerance, CoM in its box).
bool isPhysicallyConsistent(const InertialVector& phi, const ConsistencyBounds& bounds,
                            double tolerance = 1e-12) noexcept;

/// Projects φ onto the consistent set (returns true when it changed φ). A consistent φ is left
/// bit-for-bit unchanged. Allocation-free.
bool projectPhysicallyConsistent(InertialVector& phi, const ConsistencyBounds& bounds) noexcept;

/// Rotational inertia about the centre of mass of φ, in body axes (requires m > 0).
Eigen::Matrix3d inertiaAboutCom(const InertialVector& phi) noexcept;

}  // namespace mrqp::estimation
