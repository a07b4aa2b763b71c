// Generated model code against the independent slow reference (tests/reference) and against
// finite differences, on the six models (control/model/urdf, tests/data/models).
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "door_model.hpp"
#include "human_model.hpp"
#include "jvrc1_model.hpp"
#include "model/model_traits.hpp"
#include "model_files.hpp"
#include "panda_model.hpp"
#include "pendulum_model.hpp"
#include "reference_model.hpp"
#include "romeo_model.hpp"

MRQP_MODEL_TRAITS(door_model);
MRQP_MODEL_TRAITS(pendulum_model);
MRQP_MODEL_TRAITS(panda_model);
MRQP_MODEL_TRAITS(jvrc1_model);
MRQP_MODEL_TRAITS(romeo_model);
MRQP_MODEL_TRAITS(human_model);

namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using mrqp::test::ReferenceModel;

/// A vector or std::array position from an int loop index.
std::size_t ix(int i) { return static_cast<std::size_t>(i); }

std::string modelPath(const char* file) { return mrqp::testing::modelUrdf(file); }

double maxAbs(const MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

Vector3d log3(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

template <class V>
V randomVector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  V v;
  for (int i = 0; i < v.size(); ++i) v(i) = u(rng);
  return v;
}

/// Finite-difference twist of a frame between q⁻ and q⁺ (2h apart): (ω; v) of `point`.
template <class M>
Eigen::Matrix<double, 6, 1> fdTwist(typename M::Data& d, int f, const Vector3d& point,
                                    const typename M::ConfigVector& qm, const typename M::ConfigVector& qp,
                                    double h, bool world) {
  M::fk(d, qm);
  const auto Pm = M::framePose(d, f);
  M::fk(d, qp);
  const auto Pp = M::framePose(d, f);
  const Vector3d xm = Pm.p + Pm.R * point, xp = Pp.p + Pp.R * point;
  Eigen::Matrix<double, 6, 1> t;
  if (world) {
    t.head<3>() = log3(Pp.R * Pm.R.transpose()) / (2 * h);
    t.tail<3>() = (xp - xm) / (2 * h);
  } else {
    t.head<3>() = log3(Pm.R.transpose() * Pp.R) / (2 * h);
    // linear velocity expressed in the frame at the middle configuration
    const Eigen::Matrix3d Rmid = Pm.R * Eigen::AngleAxisd(0.5 * log3(Pm.R.transpose() * Pp.R).norm(),
                                                          log3(Pm.R.transpose() * Pp.R).normalized())
                                            .toRotationMatrix();
    t.tail<3>() = Rmid.transpose() * (xp - xm) / (2 * h);
  }
  return t;
}

/// Everything a generated model must satisfy, checked at several random states.
template <class M>
void checkModel(const char* file, bool floating, int expectedSingular) {
  const ReferenceModel ref = ReferenceModel::fromUrdf(modelPath(file), floating);
  auto d = std::make_unique<typename M::Data>();
  auto dm = std::make_unique<typename M::Data>();
  INFO("model " << file);

  // structure, names, limits
  REQUIRE(M::nq == ref.nq());
  REQUIRE(M::nv == ref.nv());
  REQUIRE(M::floating_base == floating);
  const auto& names = ref.jointNames();
  REQUIRE(names.size() == M::jointNames().size());
  for (size_t i = 0; i < names.size(); ++i) CHECK(names[i] == M::jointNames()[i]);
  REQUIRE(ref.frameNames().size() == static_cast<size_t>(M::nframes));
  for (int f = 0; f < M::nframes; ++f) CHECK(ref.frameNames()[ix(f)] == M::frameNames()[ix(f)]);
  for (int i = 0; i < M::nq; ++i) {
    CHECK(M::qLower()[ix(i)] == ref.lowerPositionLimit()(i));
    CHECK(M::qUpper()[ix(i)] == ref.upperPositionLimit()(i));
  }
  for (int i = 0; i < M::nv; ++i) {
    CHECK(M::vLimit()[ix(i)] == ref.velocityLimit()(i));
    CHECK(M::effortLimit()[ix(i)] == ref.effortLimit()(i));
  }
  CHECK(M::totalMass() == Approx(ref.totalMass()).epsilon(1e-12));
  CHECK(M::frameIndex(M::frameNames()[M::nframes - 1]) == M::nframes - 1);
  CHECK(M::frameIndex("no such frame") == -1);

  typename M::ParamVector phi;
  M::params(phi);
  const VectorXd phiRef = ref.inertialParameters();
  REQUIRE(phiRef.size() == phi.size());
  CHECK(maxAbs(phi - phiRef) < 1e-12 * std::max(1.0, maxAbs(phiRef)));

  std::mt19937 rng(12345);
  auto M_ = std::make_unique<typename M::MassMatrix>();
  auto Y = std::make_unique<typename M::Regressor>();
  Y->resize(M::nv, 10 * M::nbodies);
  auto J = std::make_unique<typename M::Jacobian>();
  auto Jc = std::make_unique<typename M::ComJacobian>();
  typename M::MassMatrix& Mm = *M_;
  for (int sample = 0; sample < 4; ++sample) {
    INFO("sample " << sample);
    const typename M::ConfigVector q = mrqp::model::sampleConfiguration<M>(rng);
    const auto v = randomVector<typename M::TangentVector>(rng);
    const auto a = randomVector<typename M::TangentVector>(rng);
    const VectorXd qx = q, vx = v, ax = a;

    // mass matrix: symmetric, equal to the reference (built column by column from its RNEA),
    // positive definite except along coordinates that move no mass
    M::crba(*d, q, Mm);
    const MatrixXd Mref = ref.massMatrix(qx);
    const double scale = std::max(1.0, maxAbs(Mref));
    CHECK(maxAbs(Mm - Mm.transpose()) < 1e-12 * scale);
    CHECK(maxAbs(Mm - Mref) < 1e-9 * scale);
    const MatrixXd Mdyn = Mm;
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(Mdyn);
    int singular = 0;
    for (int i = 0; i < M::nv; ++i) {
      CHECK(eig.eigenvalues()(i) > -1e-10 * scale);
      if (eig.eigenvalues()(i) < 1e-10 * scale) ++singular;
    }
    CHECK(singular == expectedSingular);

    // bias forces, inverse dynamics, τ = M a + N, regressor
    typename M::TangentVector N, tau, N0;
    M::nle(*d, q, v, N);
    M::rnea(*d, q, v, a, tau);
    const VectorXd Nref = ref.nonLinearEffects(qx, vx);
    const double fscale = std::max(1.0, maxAbs(Nref));
    CHECK(maxAbs(N - Nref) < 1e-9 * fscale);
    CHECK(maxAbs(tau - ref.rnea(qx, vx, ax)) < 1e-9 * fscale);
    CHECK(maxAbs(tau - (Mm * a + N)) < 1e-9 * fscale);
    M::regressor(*d, q, v, a, *Y);
    CHECK(maxAbs((*Y) * phi - tau) < 1e-9 * fscale);

    // Ṁ − 2C: with C v = N(q, v) − N(q, 0), vᵀ (Ṁ − 2C) v = 0 (Ṁ by central differences)
    {
      const double h = 1e-6;
      typename M::ConfigVector qp, qm;
      M::integrate(q, v, h, qp);
      M::integrate(q, v, -h, qm);
      auto Mp = std::make_unique<typename M::MassMatrix>();
      auto Mn = std::make_unique<typename M::MassMatrix>();
      M::crba(*dm, qp, *Mp);
      M::crba(*dm, qm, *Mn);
      const typename M::MassMatrix Mdot = (*Mp - *Mn) / (2 * h);
      typename M::TangentVector zero = M::TangentVector::Zero();
      M::nle(*d, q, zero, N0);
      const double lhs = v.dot(Mdot * v), rhs = 2.0 * v.dot(N - N0);
      CHECK(std::abs(lhs - rhs) < 1e-5 * std::max(1.0, std::abs(rhs)));
    }

    // Fixed base (q and v are the same coordinates): C from the Christoffel symbols of ∂M/∂q
    // (central differences) reproduces N(q, v) − N(q, 0), and Ṁ − 2C is skew-symmetric.
    if (!M::floating_base) {
      const double h = 1e-6;
      std::vector<MatrixXd> dM(M::nv);
      auto Mp = std::make_unique<typename M::MassMatrix>();
      auto Mn = std::make_unique<typename M::MassMatrix>();
      for (int k = 0; k < M::nv; ++k) {
        typename M::ConfigVector qp = q, qm = q;
        qp(k) += h;
        qm(k) -= h;
        M::crba(*dm, qp, *Mp);
        M::crba(*dm, qm, *Mn);
        dM[ix(k)] = (*Mp - *Mn) / (2 * h);
      }
      MatrixXd C = MatrixXd::Zero(M::nv, M::nv), Mdot = MatrixXd::Zero(M::nv, M::nv);
      for (int k = 0; k < M::nv; ++k) Mdot += dM[ix(k)] * v(k);
      for (int i = 0; i < M::nv; ++i)
        for (int j = 0; j < M::nv; ++j)
          for (int k = 0; k < M::nv; ++k)
            C(i, j) += 0.5 * (dM[ix(k)](i, j) + dM[ix(j)](i, k) - dM[ix(i)](j, k)) * v(k);
      typename M::TangentVector zero = M::TangentVector::Zero(), g;
      M::nle(*d, q, zero, g);
      const double cs = std::max(1.0, maxAbs(Mdot));
      CHECK(maxAbs(C * v - (N - g)) < 1e-5 * std::max(1.0, maxAbs(N - g)));
      const MatrixXd S = Mdot - 2.0 * C;
      CHECK(maxAbs(S + S.transpose()) < 1e-5 * cs);
    }

    // kinematics: poses equal the reference's; Jacobians equal the reference's and central
    // differences of the poses; J̇v equals central differences of J v
    M::fk(*d, q, v);
    for (int f = 0; f < M::nframes; ++f) {
      INFO("frame " << M::frameNames()[ix(f)]);
      const auto P = M::framePose(*d, f);
      const auto Pref = ref.framePose(qx, M::frameNames()[ix(f)]);
      CHECK(maxAbs(P.R - Pref.R) < 1e-12);
      CHECK(maxAbs(P.p - Pref.p) < 1e-12);
    }
    const Vector3d point(0.05, -0.02, 0.03);
    const double h = 1e-6;
    typename M::ConfigVector qp, qm;
    M::integrate(q, v, h, qp);
    M::integrate(q, v, -h, qm);
    for (int f = 0; f < M::nframes; f += (M::nframes > 12 ? 5 : 1)) {
      for (bool world : {false, true}) {
        INFO("frame " << M::frameNames()[ix(f)] << (world ? " world-aligned" : " local"));
        M::fk(*d, q, v);
        M::jacobian(*d, f, point, world, *J);
        const MatrixXd Jref = ref.frameJacobian(qx, M::frameNames()[ix(f)], point, world);
        CHECK(maxAbs(*J - Jref) < 1e-10);
        const Eigen::Matrix<double, 6, 1> twist = (*J) * v;
        const auto fd = fdTwist<M>(*dm, f, point, qm, qp, h, world);
        CHECK(maxAbs(twist - fd) < 1e-6 * std::max(1.0, maxAbs(twist)));
        const auto bias = M::bias(*d, f, point, world);
        const auto biasRef = ref.frameBiasAcceleration(qx, vx, M::frameNames()[ix(f)], point, world);
        CHECK(maxAbs(bias - biasRef) < 1e-9 * std::max(1.0, maxAbs(biasRef)));
        M::fk(*dm, qp);
        M::jacobian(*dm, f, point, world, *J);
        const Eigen::Matrix<double, 6, 1> tp = (*J) * v;
        M::fk(*dm, qm);
        M::jacobian(*dm, f, point, world, *J);
        const Eigen::Matrix<double, 6, 1> tm = (*J) * v;
        CHECK(maxAbs(bias - (tp - tm) / (2 * h)) < 1e-5 * std::max(1.0, maxAbs(bias)));
      }
    }

    // centre of mass: a mass-weighted sum of link CoMs in the reference; Jacobian by differences
    M::fk(*d, q);
    const Vector3d c = M::com(*d);
    CHECK(maxAbs(c - ref.centerOfMass(qx)) < 1e-12);
    M::comJacobian(*d, *Jc);
    CHECK(maxAbs(*Jc - ref.comJacobian(qx)) < 1e-10);
    M::fk(*dm, qp);
    const Vector3d cp = M::com(*dm);
    M::fk(*dm, qm);
    const Vector3d cm = M::com(*dm);
    CHECK(maxAbs((*Jc) * v - (cp - cm) / (2 * h)) < 1e-6);
  }
}

}  // namespace

TEST_CASE("generated door matches the reference", "[model_gen]") {
  checkModel<door_model_model>("door.urdf", false, 0);
}

TEST_CASE("generated double pendulum (continuous joints) matches the reference", "[model_gen]") {
  checkModel<pendulum_model_model>("double-pendulum-continuous.urdf", false, 0);
}

TEST_CASE("generated Panda (prismatic, mimic finger) matches the reference", "[model_gen]") {
  checkModel<panda_model_model>("panda.urdf", false, 0);
}

TEST_CASE("generated JVRC-1 with free-flyer matches the reference", "[model_gen]") {
  checkModel<jvrc1_model_model>("jvrc1.urdf", true, 0);
}

TEST_CASE("generated Romeo matches the reference; its massless hands make M singular twice", "[model_gen]") {
  checkModel<romeo_model_model>("romeo.urdf", false, 2);
}

TEST_CASE("generated 48-dof human with free-flyer matches the reference", "[model_gen]") {
  checkModel<human_model_model>("human-subject01-48dof.urdf", true, 0);
}

TEST_CASE("integrate moves a free-flyer along the exponential of its body twist", "[model_gen]") {
  using M = jvrc1_model_model;
  M::ConfigVector q, q1, q2, q3;
  M::neutral(q);
  M::TangentVector v = M::TangentVector::Zero();
  v(2) = 0.7;  // yaw rate in the base frame
  v(3) = 1.0;  // forward speed in the base frame
  // half a turn: the base ends at (0, 2/ω, 0) with yaw π (a circle of radius 1/ω)
  M::integrate(q, v, M_PI / 0.7, q1);
  CHECK(q1(0) == Approx(0.0).margin(1e-12));
  CHECK(q1(1) == Approx(2.0 / 0.7).epsilon(1e-12));
  CHECK(std::abs(q1(3)) == Approx(0.0).margin(1e-12));
  CHECK(std::abs(q1(6)) == Approx(1.0).epsilon(1e-12));
  // composition: two half steps equal one step
  M::integrate(q, v, 0.3, q2);
  M::integrate(q2, v, 0.3, q3);
  M::integrate(q, v, 0.6, q2);
  CHECK((q3 - q2).cwiseAbs().maxCoeff() < 1e-12);
}
