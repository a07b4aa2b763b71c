// The Newton–Euler equation of one rigid body as a linear map of its inertial parameters
// (paper 1, eq. 47 and 51 for one link): wrench = Y(v, a) φ.
//
// Conventions are those of the generated models and of RigidObject: spatial vectors are
// (angular; linear) in body axes at the body origin, φ = (m, hx, hy, hz, Ixx, Ixy, Iyy, Ixz, Iyz,
// Izz) with h = m c the first moment and I the rotational inertia about the body origin. `a` is
// the body acceleration (ω̇, v̇) with gravity folded in (v̇ − g_body), so that the wrench is the
// one the environment applies to the body.
#pragma once

#include <Eigen/Core>

namespace mrqp::estimation {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using InertialVector = Eigen::Matrix<double, 10, 1>;
using BodyRegressor = Eigen::Matrix<double, 6, 10>;

/// The 6 × 6 spatial inertia at the body origin of any φ (physical or not):
/// [[I, [h]×], [[h]×ᵀ, m 1]].
Matrix6d spatialInertiaOf(const InertialVector& phi) noexcept;

/// Y such that Y φ = I(φ) a + v ×* I(φ) v for every φ. Allocation-free.
void rigidBodyRegressor(const Vector6d& v, const Vector6d& a, BodyRegressor& Y) noexcept;

}  // namespace mrqp::estimation
