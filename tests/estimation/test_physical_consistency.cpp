// The consistency projection: what it keeps, what it repairs, and the triangle inequality.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "estimation/physical_consistency.hpp"

using namespace mrqp::estimation;

namespace {

/// φ of a solid box of mass m, sides (a, b, c), centre c0, rotated by R, about the origin.
InertialVector boxParameters(double m, const Eigen::Vector3d& sides, const Eigen::Vector3d& c0,
                             const Eigen::Matrix3d& R) {
  const Eigen::Vector3d s2 = sides.cwiseAbs2();
  const Eigen::Vector3d J(m / 12.0 * (s2.y() + s2.z()), m / 12.0 * (s2.x() + s2.z()),
                          m / 12.0 * (s2.x() + s2.y()));
  const Eigen::Matrix3d Ic = R * J.asDiagonal() * R.transpose();
  const Eigen::Matrix3d Io = Ic + m * (c0.squaredNorm() * Eigen::Matrix3d::Identity() - c0 * c0.transpose());
  InertialVector phi;
  phi << m, m * c0.x(), m * c0.y(), m * c0.z(), Io(0, 0), Io(0, 1), Io(1, 1), Io(0, 2), Io(1, 2), Io(2, 2);
  return phi;
}

Eigen::Vector3d principalMoments(const InertialVector& phi) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertiaAboutCom(phi)).eigenvalues();
}

}  // namespace

TEST_CASE("A real body's parameters are consistent and left unchanged", "[estimation][consistency]") {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  InertialVector phi =
      boxParameters(0.941, Eigen::Vector3d(0.3, 0.2, 0.15), Eigen::Vector3d(0.01, -0.02, 0.03), R);
  const InertialVector before = phi;
  ConsistencyBounds bounds;
  CHECK(isPhysicallyConsistent(phi, bounds));
  CHECK_FALSE(projectPhysicallyConsistent(phi, bounds));
  CHECK(phi == before);
}

TEST_CASE("The projection repairs negative mass, indefinite inertia and the triangle inequality",
          "[estimation][consistency]") {
  ConsistencyBounds bounds;
  SECTION("principal moments violating J1 + J2 >= J3") {
    // A diagonal inertia (1, 1, 3) about the CoM: PD but 1 + 1 < 3, no mass distribution has it.
    InertialVector phi = InertialVector::Zero();
    phi(0) = 2.0;
    phi(4) = 1.0;
    phi(6) = 1.0;
    phi(9) = 3.0;
    CHECK_FALSE(isPhysicallyConsistent(phi, bounds));
    CHECK(projectPhysicallyConsistent(phi, bounds));
    CHECK(isPhysicallyConsistent(phi, bounds, 1e-12));
    const Eigen::Vector3d J = principalMoments(phi);
    CHECK(J(0) + J(1) >= J(2) - 1e-12);
    CHECK(J.minCoeff() > 0.0);
    CHECK(phi(0) == 2.0);  // the mass is kept
  }
  SECTION("negative mass and an indefinite inertia, with the CoM kept in its box") {
    InertialVector phi;
    phi << -0.5, 0.3, 0.0, 0.0, -1.0, 0.2, 0.5, 0.0, 0.1, 0.4;
    bounds.bound_com = true;
    bounds.com_lower = Eigen::Vector3d::Constant(-0.1);
    bounds.com_upper = Eigen::Vector3d::Constant(0.1);
    CHECK(projectPhysicallyConsistent(phi, bounds));
    CHECK(isPhysicallyConsistent(phi, bounds, 1e-12));
    CHECK(phi(0) == bounds.min_mass);
  }
  SECTION("random parameter vectors all land in the consistent set, and projecting twice changes nothing") {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int trial = 0; trial < 500; ++trial) {
      InertialVector phi;
      for (int i = 0; i < 10; ++i) phi(i) = u(rng);
      projectPhysicallyConsistent(phi, bounds);
      REQUIRE(isPhysicallyConsistent(phi, bounds, 1e-9));
      const InertialVector once = phi;
      projectPhysicallyConsistent(phi, bounds);
      REQUIRE((phi - once).norm() <= 1e-12 * (1.0 + once.norm()));
    }
  }
  SECTION("non-finite input becomes a consistent minimal body") {
    InertialVector phi = InertialVector::Constant(std::nan(""));
    CHECK(projectPhysicallyConsistent(phi, bounds));
    CHECK(isPhysicallyConsistent(phi, bounds, 1e-12));
  }
}
