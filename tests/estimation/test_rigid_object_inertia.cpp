// RigidObject's inertial setters (setInertia, setInertialParameters), with which the estimator
// writes a learned mass and CoM into the QP's model: after the setter the object's dynamics (M, N,
// CoM, its Jacobian and bias) equal those of an object built afresh with the new parameters at the
// same state (the independent reference), a refused input changes nothing, and the setters
// allocate nothing (counting allocator; Eigen's run-time check armed where compiled in).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>

#include "counting_allocator.hpp"
#include "problem/rigid_object.hpp"

using mrqp::problem::RigidObject;

namespace {

void setState(RigidObject& o, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  o.q() = q;
  o.v() = v;
  o.update();
}

void checkSame(const RigidObject& a, const RigidObject& b) {
  CHECK(a.mass() == Approx(b.mass()).epsilon(1e-15));
  CHECK((a.massMatrix() - b.massMatrix()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.bias() - b.bias()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.com() - b.com()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.comJacobian() - b.comJacobian()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.comBias() - b.comBias()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((a.inertialParameters() - b.inertialParameters()).cwiseAbs().maxCoeff() < 1e-12);
}

Eigen::Matrix3d randomInertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.01, 0.1);
  const Eigen::Vector3d d(u(rng), u(rng), u(rng));
  // Principal moments satisfying the triangle inequality: from a random mass distribution's Σ.
  const Eigen::Vector3d J(d.y() + d.z(), d.x() + d.z(), d.x() + d.y());
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(u(rng) * 30.0, Eigen::Vector3d(u(rng), -u(rng), u(rng)).normalized()).toRotationMatrix();
  return R * J.asDiagonal() * R.transpose();
}

}  // namespace

TEST_CASE("RigidObject::setInertia gives the dynamics of an object built with those parameters",
          "[estimation][rigid_object]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double m0 = 0.1, m1 = 0.941 + 0.5 * u(rng);
    const Eigen::Vector3d c0(0, 0, 0), c1(0.05 * u(rng), 0.08 * u(rng), 0.03 * u(rng));
    const Eigen::Matrix3d I0 = randomInertia(rng), I1 = randomInertia(rng);
    RigidObject changed("box", m0, c0, I0);
    changed.setGravity(Eigen::Vector3d(0.1, -0.2, -9.81));
    RigidObject fresh("box", m1, c1, I1);
    fresh.setGravity(Eigen::Vector3d(0.1, -0.2, -9.81));

    Eigen::VectorXd q(7), v(6);
    const Eigen::Quaterniond rot(Eigen::AngleAxisd(3.0 * u(rng), Eigen::Vector3d(u(rng), u(rng), 1).normalized()));
    q << u(rng), u(rng), 1.0 + u(rng), rot.w(), rot.x(), rot.y(), rot.z();
    for (int k = 0; k < 6; ++k) v(k) = 2.0 * u(rng);
    setState(changed, q, v);
    setState(fresh, q, v);
    REQUIRE((changed.bias() - fresh.bias()).norm() > 1e-3);  // the two differ before the setter

    REQUIRE(changed.setInertia(m1, c1, I1));
    checkSame(changed, fresh);  // the setter updates the current state's dynamics itself
    CHECK((changed.inertiaAboutCom() - I1).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((changed.localCom() - c1).cwiseAbs().maxCoeff() < 1e-15);
    // And at another state, through update().
    Eigen::VectorXd v2 = v.reverse();
    setState(changed, q, v2);
    setState(fresh, q, v2);
    checkSame(changed, fresh);

    // From the parameters about the origin (the estimator's layout).
    RigidObject from_phi("box", m0, c0, I0);
    from_phi.setGravity(Eigen::Vector3d(0.1, -0.2, -9.81));
    setState(from_phi, q, v2);
    REQUIRE(from_phi.setInertialParameters(fresh.inertialParameters()));
    checkSame(from_phi, fresh);
    CHECK((from_phi.inertiaAboutCom() - I1).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("RigidObject's inertial setters refuse what the constructor refuses and change nothing",
          "[estimation][rigid_object]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix3d I = Eigen::Vector3d(0.047, 0.021, 0.054).asDiagonal();
  RigidObject o("box", 2.0, Eigen::Vector3d(0.01, 0, 0), I);
  const RigidObject::InertialParameters before = o.inertialParameters();
  const Eigen::VectorXd N = o.bias();
  CHECK_FALSE(o.setInertia(0.0, Eigen::Vector3d::Zero(), I));
  CHECK_FALSE(o.setInertia(-1.0, Eigen::Vector3d::Zero(), I));
  CHECK_FALSE(o.setInertia(nan, Eigen::Vector3d::Zero(), I));
  CHECK_FALSE(o.setInertia(1.0, Eigen::Vector3d(nan, 0, 0), I));
  CHECK_FALSE(o.setInertia(1.0, Eigen::Vector3d::Zero(), -I));
  Eigen::Matrix3d asym = I;
  asym(0, 1) = 1e-3;
  CHECK_FALSE(o.setInertia(1.0, Eigen::Vector3d::Zero(), asym));
  RigidObject::InertialParameters phi = before;
  phi(0) = 0.0;
  CHECK_FALSE(o.setInertialParameters(phi));
  phi = before;
  phi(4) = -1.0;  // I_O not positive: I_c neither
  CHECK_FALSE(o.setInertialParameters(phi));
  CHECK(o.inertialParameters() == before);
  CHECK(o.bias() == N);
}

TEST_CASE("RigidObject's inertial setters allocate nothing", "[estimation][rigid_object][realtime]") {
  const Eigen::Matrix3d I = Eigen::Vector3d(0.047, 0.021, 0.054).asDiagonal();
  RigidObject o("box", 0.1, Eigen::Vector3d::Zero(), I);
  RigidObject::InertialParameters phi = o.inertialParameters();
  int ok = 0;
  const long allocations = mrqp::testing::allocationsIn([&] {
    for (int k = 0; k < 1000; ++k) {
      const double m = 0.1 + 1e-3 * k;
      ok += o.setInertia(m, Eigen::Vector3d(0.001 * k, 0.0, -0.02), I) ? 1 : 0;
      phi(0) = m;
      phi(1) = 0.01 * m;
      ok += o.setInertialParameters(phi) ? 1 : 0;
      o.update();
    }
  });
  CHECK(ok == 2000);
  CHECK(allocations == 0);
  CHECK(mrqp::testing::allocationsIn([] { delete new volatile int(3); }) >= 1);  // the counter counts
}
