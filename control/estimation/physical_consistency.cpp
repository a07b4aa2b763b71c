// Projection of inertial parameters onto the physically consistent set (see the header).
#include "estimation/physical_consistency.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mrqp::estimation {
namespace {

Eigen::Matrix3d rotationalInertia(const InertialVector& phi) noexcept {
  Eigen::Matrix3d I;
  I << phi(4), phi(5), phi(7), phi(5), phi(6), phi(8), phi(7), phi(8), phi(9);
  return I;
}

void setRotationalInertia(InertialVector& phi, const Eigen::Matrix3d& I) noexcept {
  phi(4) = I(0, 0);
  phi(5) = 0.5 * (I(0, 1) + I(1, 0));
  phi(6) = I(1, 1);
  phi(7) = 0.5 * (I(0, 2) + I(2, 0));
  phi(8) = 0.5 * (I(1, 2) + I(2, 1));
  phi(9) = I(2, 2);
}

/// m ([c]×ᵀ[c]×) = m (cᵀc 1 − c cᵀ): the parallel-axis term.
Eigen::Matrix3d parallelAxis(double m, const Eigen::Vector3d& c) noexcept {
  return m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
}

Eigen::Matrix3d secondMoments(const Eigen::Matrix3d& Ic) noexcept {
  return 0.5 * Ic.trace() * Eigen::Matrix3d::Identity() - Ic;
}

}  // namespace

Eigen::Matrix3d inertiaAboutCom(const InertialVector& phi) noexcept {
  const Eigen::Vector3d c = phi.segment<3>(1) / phi(0);
  return rotationalInertia(phi) - parallelAxis(phi(0), c);
}

bool isPhysicallyConsistent(const InertialVector& phi, const ConsistencyBounds& bounds,
                            double tolerance) noexcept {
  if (!phi.allFinite() || phi(0) < bounds.min_mass) return false;
  const Eigen::Vector3d c = phi.segment<3>(1) / phi(0);
  if (bounds.bound_com &&
      ((c - bounds.com_lower).minCoeff() < -tolerance || (bounds.com_upper - c).minCoeff() < -tolerance))
    return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(secondMoments(inertiaAboutCom(phi)),
                                                           Eigen::EigenvaluesOnly);
  return eig.eigenvalues().minCoeff() >= bounds.min_second_moment - tolerance;
}

bool projectPhysicallyConsistent(InertialVector& phi, const ConsistencyBounds& bounds) noexcept {
  if (isPhysicallyConsistent(phi, bounds, 0.0)) return false;
  // Mass and centre of mass first; a non-finite or non-positive mass keeps the CoM at the origin.
  const bool mass_usable = std::isfinite(phi(0)) && phi(0) > 0.0 && phi.segment<3>(1).allFinite();
  Eigen::Vector3d c = mass_usable ? Eigen::Vector3d(phi.segment<3>(1) / phi(0)) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d Ic =
      mass_usable && phi.tail<6>().allFinite() ? inertiaAboutCom(phi) : Eigen::Matrix3d::Zero();
  const double m = std::max(std::isfinite(phi(0)) ? phi(0) : bounds.min_mass, bounds.min_mass);
  if (bounds.bound_com) c = c.cwiseMax(bounds.com_lower).cwiseMin(bounds.com_upper);
  // Inertia about the CoM: clamp the second moments, map back.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(secondMoments(Ic));
  const Eigen::Vector3d s = eig.eigenvalues().cwiseMax(bounds.min_second_moment);
  const Eigen::Matrix3d sigma = eig.eigenvectors() * s.asDiagonal() * eig.eigenvectors().transpose();
  Ic = sigma.trace() * Eigen::Matrix3d::Identity() - sigma;
  phi(0) = m;
  phi.segment<3>(1) = m * c;
  setRotationalInertia(phi, Ic + parallelAxis(m, c));
  return true;
}

}  // namespace mrqp::estimation
