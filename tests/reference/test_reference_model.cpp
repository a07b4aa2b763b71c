// Tests of the slow reference model against independent facts: closed-form pendulums, finite
// differences of kinematics and energies, Jacobian-based mass matrix and gravity torques.
#include "model_files.hpp"
#include "reference_model.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using mrqp::test::ReferenceModel;
using Vector6d = ReferenceModel::Vector6d;

const std::string kDataDir = MRQP_TEST_DATA_DIR;
constexpr double kG = 9.81;

// "models/FILE": a robot model (control/model/urdf or tests/data/models); else under tests/data.
ReferenceModel load(const std::string& relative, bool floating_base) {
  const std::string models = "models/";
  if (relative.compare(0, models.size(), models) == 0)
    return ReferenceModel::fromUrdf(mrqp::testing::modelUrdf(relative.substr(models.size())), floating_base);
  return ReferenceModel::fromUrdf(kDataDir + "/" + relative, floating_base);
}

std::vector<std::string> modelFiles() {
  std::vector<std::string> files;
  for (const std::string& name : mrqp::testing::modelUrdfNames()) files.push_back("models/" + name);
  return files;
}

struct Case {
  std::string file;
  bool floating_base;
  ReferenceModel model;
};

// Every model file, fixed and floating base, plus the small models of tests/data/reference.
std::vector<Case> allCases() {
  std::vector<std::string> files = modelFiles();
  for (const char* extra :
       {"reference/pendulum.urdf", "reference/double_pendulum.urdf", "reference/mimic_chain.urdf"})
    files.push_back(extra);
  std::vector<Case> cases;
  for (const std::string& file : files)
    for (bool fb : {false, true}) cases.push_back({file, fb, load(file, fb)});
  return cases;
}

Eigen::VectorXd randomVector(Eigen::Index n, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x(i) = u(rng);
  return x;
}

// Joints uniformly within their limits ([-pi, pi] when unbounded), random base pose.
Eigen::VectorXd randomConfig(const ReferenceModel& m, std::mt19937& rng) {
  Eigen::VectorXd q = m.neutral();
  const Eigen::VectorXd lo = m.lowerPositionLimit(), hi = m.upperPositionLimit();
  const int first = m.floatingBase() ? 7 : 0;
  for (int i = first; i < m.nq(); ++i) {
    const double a = std::isfinite(lo(i)) ? lo(i) : -M_PI;
    const double b = std::isfinite(hi(i)) ? hi(i) : M_PI;
    q(i) = std::uniform_real_distribution<double>(0.0, 1.0)(rng) * (b - a) + a;
  }
  if (m.floatingBase()) {
    q.head<3>() = randomVector(3, rng);
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::Vector4d quat(n(rng), n(rng), n(rng), n(rng));
    q.segment<4>(3) = quat.normalized();
  }
  return q;
}

Eigen::Vector3d vee(const Eigen::Matrix3d& W) {
  const Eigen::Matrix3d A = 0.5 * (W - W.transpose());
  return Eigen::Vector3d(A(2, 1), A(0, 2), A(1, 0));
}

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

// Velocity (omega; v) of a point of a frame by central differences along integrate(q, v, +-h).
Vector6d fdPointVelocity(const ReferenceModel& m, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                         const std::string& frame, const Eigen::Vector3d& point, bool world_aligned,
                         double h) {
  const auto P0 = m.framePose(q, frame);
  const auto Pp = m.framePose(m.integrate(q, v, h), frame);
  const auto Pm = m.framePose(m.integrate(q, v, -h), frame);
  const Eigen::Matrix3d Rdot = (Pp.R - Pm.R) / (2 * h);
  const Eigen::Vector3d pdot = ((Pp.p + Pp.R * point) - (Pm.p + Pm.R * point)) / (2 * h);
  Vector6d out;
  if (world_aligned)
    out << vee(Rdot * P0.R.transpose()), pdot;
  else
    out << vee(P0.R.transpose() * Rdot), P0.R.transpose() * pdot;
  return out;
}

// Spatial inertia about the body origin from (m, h = m c, Ixx, Ixy, Iyy, Ixz, Iyz, Izz).
Eigen::Matrix<double, 6, 6> spatialInertia(const Eigen::Matrix<double, 10, 1>& phi) {
  const double m = phi(0);
  const Eigen::Vector3d h = phi.segment<3>(1);
  Eigen::Matrix3d I;
  I << phi(4), phi(5), phi(7), phi(5), phi(6), phi(8), phi(7), phi(8), phi(9);
  Eigen::Matrix<double, 6, 6> S;
  S << I, skew(h), skew(h).transpose(), m * Eigen::Matrix3d::Identity();
  return S;
}

double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / (1.0 + b.norm());
}

Eigen::Matrix3d rotX(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d rotY(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rotZ(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

}  // namespace

// -----------------------------------------------------------------------------------------------
// Closed forms
// -----------------------------------------------------------------------------------------------

TEST_CASE("single pendulum matches the closed form", "[reference]") {
  const ReferenceModel m = load("reference/pendulum.urdf", false);
  REQUIRE(m.nq() == 1);
  REQUIRE(m.nv() == 1);
  REQUIRE(m.jointNames() == std::vector<std::string>{"hinge"});
  REQUIRE(m.frameNames() == std::vector<std::string>{"base", "arm"});

  const double mass = 1.3, l = 0.7, yaw = 0.4;
  // Inertia about the joint axis (link x): the tensor diag(0.05, 0.02, 0.03) turned by yaw about z.
  const double Ixx = 0.05 * std::cos(yaw) * std::cos(yaw) + 0.02 * std::sin(yaw) * std::sin(yaw);
  CHECK(m.totalMass() == Approx(mass));

  std::mt19937 rng(11);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(1, rng, 2.0),
                          a = randomVector(1, rng, 2.0);
    const double th = q(0);
    CHECK(m.massMatrix(q)(0, 0) == Approx(Ixx + mass * l * l).epsilon(1e-12));
    CHECK(m.nonLinearEffects(q, v)(0) == Approx(mass * kG * l * std::sin(th)).margin(1e-12));
    CHECK(m.rnea(q, v, a)(0) ==
          Approx((Ixx + mass * l * l) * a(0) + mass * kG * l * std::sin(th)).margin(1e-12));

    // URDF convention: child = origin(xyz, Rz(yaw) Ry(pitch) Rx(roll)) * rotation about the
    // normalised axis (here x of the joint frame).
    const auto P = m.framePose(q, "arm");
    CHECK(relErr(P.R, rotZ(M_PI / 2) * rotX(th)) < 1e-14);
    CHECK(relErr(P.p, Eigen::Vector3d(0.1, -0.2, 0.3)) < 1e-14);
    const Eigen::Vector3d com = m.centerOfMass(q);
    CHECK(relErr(com, Eigen::Vector3d(0.1 - l * std::sin(th), -0.2, 0.3 - l * std::cos(th))) < 1e-14);
  }
}

TEST_CASE("planar double pendulum matches the textbook formulas", "[reference]") {
  const ReferenceModel m = load("reference/double_pendulum.urdf", false);
  REQUIRE(m.jointNames() == std::vector<std::string>{"shoulder", "elbow"});
  REQUIRE(m.frameNames() == std::vector<std::string>{"base", "upper", "lower", "tip"});
  REQUIRE(m.bodyNames() == std::vector<std::string>{"base", "upper", "lower"});
  REQUIRE(m.frameBody() == std::vector<int>{0, 1, 2, 2});

  const double m1 = 1.2, lc1 = 0.35, l1 = 0.8, I1 = 0.07;
  const double m2 = 0.9, lc2 = 0.45, I2 = 0.04, ltip = 0.9;

  // Continuous joint: unbounded, no <limit> element: infinite velocity / effort limits.
  CHECK(std::isinf(m.lowerPositionLimit()(0)));
  CHECK(std::isinf(m.upperPositionLimit()(0)));
  CHECK(std::isinf(m.velocityLimit()(0)));
  CHECK(m.lowerPositionLimit()(1) == -3.0);
  CHECK(m.upperPositionLimit()(1) == 3.0);
  CHECK(m.velocityLimit()(1) == 4.0);
  CHECK(m.effortLimit()(1) == 5.0);

  std::mt19937 rng(12);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(2, rng, 2.0);
    const double q1 = q(0), q2 = q(1), qd1 = v(0), qd2 = v(1);
    const double c2 = std::cos(q2), s2 = std::sin(q2);

    Eigen::Matrix2d M;
    M(0, 0) = I1 + I2 + m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2);
    M(0, 1) = M(1, 0) = I2 + m2 * (lc2 * lc2 + l1 * lc2 * c2);
    M(1, 1) = I2 + m2 * lc2 * lc2;
    const double hc = m2 * l1 * lc2 * s2;
    Eigen::Vector2d C(-hc * (2 * qd1 * qd2 + qd2 * qd2), hc * qd1 * qd1);
    Eigen::Vector2d G(kG * ((m1 * lc1 + m2 * l1) * std::sin(q1) + m2 * lc2 * std::sin(q1 + q2)),
                      kG * m2 * lc2 * std::sin(q1 + q2));

    CHECK(relErr(m.massMatrix(q), M) < 1e-13);
    CHECK(relErr(m.nonLinearEffects(q, v), C + G) < 1e-13);
    CHECK(relErr(m.nonLinearEffects(q, Eigen::VectorXd::Zero(2)), G) < 1e-13);

    const auto tip = m.framePose(q, "tip");
    CHECK(relErr(tip.p, Eigen::Vector3d(-l1 * std::sin(q1) - ltip * std::sin(q1 + q2), 0.0,
                                        -l1 * std::cos(q1) - ltip * std::cos(q1 + q2))) < 1e-14);
    CHECK(relErr(tip.R, rotY(q1 + q2)) < 1e-14);
  }
}

// -----------------------------------------------------------------------------------------------
// Ordering, mimic joints, limits, errors
// -----------------------------------------------------------------------------------------------

TEST_CASE("mimic chains are resolved and ordering is DFS by joint name", "[reference]") {
  const ReferenceModel m = load("reference/mimic_chain.urdf", false);
  const ReferenceModel free = load("reference/mimic_chain_free.urdf", false);

  CHECK(m.frameNames() == std::vector<std::string>{"base", "h1", "h2", "h3", "tip", "s1", "s2"});
  CHECK(m.fullJointNames() ==
        std::vector<std::string>{"a_hinge", "c_follow", "d_follow", "b_slide", "f_slide"});
  CHECK(m.jointNames() == std::vector<std::string>{"a_hinge", "b_slide"});
  CHECK(m.bodyNames() == std::vector<std::string>{"base", "h1", "h2", "h3", "s1", "s2"});
  CHECK(free.jointNames() == m.fullJointNames());

  // c = 2 a + 0.1, d = -0.5 c + 0.2 = -a + 0.15, f = 3 d = -3 a + 0.45.
  Eigen::MatrixXd G(5, 2);
  G << 1, 0, 2, 0, -1, 0, 0, 1, -3, 0;
  Eigen::VectorXd off(5);
  off << 0, 0.1, 0.15, 0, 0.45;
  CHECK(relErr(m.mimicMatrix(), G) < 1e-15);
  CHECK(relErr(m.mimicOffset(), off) < 1e-15);

  std::mt19937 rng(13);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(2, rng), a = randomVector(2, rng);
    const Eigen::VectorXd qf = G * q + off, vf = G * v, af = G * a;
    CHECK(relErr(m.fullJointPositions(q), qf) < 1e-15);
    for (const std::string& frame : m.frameNames()) {
      const auto P = m.framePose(q, frame), Pf = free.framePose(qf, frame);
      CHECK(relErr(P.R, Pf.R) < 1e-14);
      CHECK(relErr(P.p, Pf.p) < 1e-14);
      CHECK(relErr(m.frameJacobian(q, frame, Eigen::Vector3d(0.1, 0.2, 0.3), true),
                   free.frameJacobian(qf, frame, Eigen::Vector3d(0.1, 0.2, 0.3), true) * G) < 1e-13);
    }
    // Constrained dynamics: M = G^T M_free G, tau = G^T tau_free.
    CHECK(relErr(m.massMatrix(q), G.transpose() * free.massMatrix(qf) * G) < 1e-13);
    CHECK(relErr(m.rnea(q, v, a), G.transpose() * free.rnea(qf, vf, af)) < 1e-13);

    // URDF rpy convention on b_slide's origin: R = Rz(0.7) Ry(0.5) Rx(0.3).
    const Eigen::Matrix3d R = rotZ(0.7) * rotY(0.5) * rotX(0.3);
    const auto s1 = m.framePose(q, "s1");
    CHECK(relErr(s1.R, R) < 1e-14);
    CHECK(relErr(s1.p, Eigen::Vector3d(0.1, 0, 0) + R * Eigen::Vector3d(0, 0, q(1))) < 1e-14);
  }
}

TEST_CASE("mimic joints of the robot models have no coordinate", "[reference]") {
  const ReferenceModel panda = load("models/panda.urdf", false);
  const auto& names = panda.jointNames();
  CHECK(std::find(names.begin(), names.end(), "panda_finger_joint2") == names.end());
  CHECK(std::find(names.begin(), names.end(), "panda_finger_joint1") != names.end());
  CHECK(panda.nv() == 8);
  CHECK(panda.fullJointNames().size() == 9);
  const ReferenceModel panda_fb = load("models/panda.urdf", true);
  CHECK(panda_fb.nq() == 15);
  CHECK(panda_fb.nv() == 14);

  // README: jvrc1 44 revolute (10 mimic), romeo 55 revolute (22 mimic).
  const ReferenceModel jvrc = load("models/jvrc1.urdf", true);
  CHECK(jvrc.fullJointNames().size() == 44);
  CHECK(jvrc.nv() == 6 + 34);
  CHECK(jvrc.nq() == 7 + 34);
  const ReferenceModel romeo = load("models/romeo.urdf", false);
  CHECK(romeo.fullJointNames().size() == 55);
  CHECK(romeo.nv() == 33);

  // Each mimic row of G has exactly one non-zero: the multiplier (no chains in these files).
  for (const ReferenceModel* m : {&panda, &jvrc, &romeo}) {
    const Eigen::MatrixXd& G = m->mimicMatrix();
    for (Eigen::Index i = 0; i < G.rows(); ++i) {
      int nonzero = 0;
      for (Eigen::Index j = 0; j < G.cols(); ++j) nonzero += G(i, j) != 0.0 ? 1 : 0;
      CHECK(nonzero == 1);
    }
  }
  const auto col = [](const ReferenceModel& m, const std::string& j) {
    const auto& n = m.jointNames();
    return static_cast<Eigen::Index>(std::find(n.begin(), n.end(), j) - n.begin());
  };
  const auto row = [](const ReferenceModel& m, const std::string& j) {
    const auto& n = m.fullJointNames();
    return static_cast<Eigen::Index>(std::find(n.begin(), n.end(), j) - n.begin());
  };
  CHECK(panda.mimicMatrix()(row(panda, "panda_finger_joint2"), col(panda, "panda_finger_joint1")) == 1.0);
  CHECK(jvrc.mimicMatrix()(row(jvrc, "R_LTHUMB"), col(jvrc, "R_UTHUMB")) == 3.0);
  CHECK(romeo.mimicMatrix()(row(romeo, "LThumb1"), col(romeo, "LHand")) == -1.0);
}

TEST_CASE("limits and neutral configuration", "[reference]") {
  const ReferenceModel m = load("models/panda.urdf", true);
  const Eigen::VectorXd lo = m.lowerPositionLimit(), hi = m.upperPositionLimit();
  REQUIRE(lo.size() == m.nq());
  REQUIRE(m.velocityLimit().size() == m.nv());
  REQUIRE(m.effortLimit().size() == m.nv());
  for (int i = 0; i < 7; ++i) {
    CHECK(lo(i) == -std::numeric_limits<double>::infinity());
    CHECK(hi(i) == std::numeric_limits<double>::infinity());
  }
  for (int i = 0; i < 6; ++i) {
    CHECK(m.velocityLimit()(i) == std::numeric_limits<double>::infinity());
    CHECK(m.effortLimit()(i) == std::numeric_limits<double>::infinity());
  }
  REQUIRE(m.jointNames()[3] == "panda_joint4");
  CHECK(lo(7 + 3) == -3.0718);
  CHECK(hi(7 + 3) == -0.0698);
  CHECK(m.velocityLimit()(6 + 3) == 2.1750);
  CHECK(m.effortLimit()(6 + 3) == 87.0);

  Eigen::VectorXd n = Eigen::VectorXd::Zero(m.nq());
  n(3) = 1.0;
  CHECK(m.neutral() == n);
  const auto root = m.framePose(m.neutral(), "panda_link0");
  CHECK(root.R == Eigen::Matrix3d::Identity());
  CHECK(root.p == Eigen::Vector3d::Zero());
}

TEST_CASE("unsupported or inconsistent input throws", "[reference]") {
  CHECK_THROWS_AS(load("reference/does_not_exist.urdf", false), std::runtime_error);
  CHECK_THROWS_AS(load("reference/bad_planar.urdf", false), std::runtime_error);
  CHECK_THROWS_AS(load("reference/bad_mimic_cycle.urdf", false), std::runtime_error);
  CHECK_THROWS_AS(load("reference/bad_mimic_unknown.urdf", false), std::runtime_error);
  CHECK_THROWS_AS(load("reference/bad_zero_axis.urdf", false), std::runtime_error);
  const ReferenceModel m = load("reference/pendulum.urdf", false);
  CHECK(m.frameIndex("nope") == -1);
  CHECK_THROWS_AS(m.framePose(m.neutral(), "nope"), std::runtime_error);
  CHECK_THROWS_AS(m.massMatrix(Eigen::VectorXd::Zero(3)), std::runtime_error);
  CHECK_THROWS_AS(m.rnea(m.neutral(), Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(1)),
                  std::runtime_error);
}

// -----------------------------------------------------------------------------------------------
// Every model, fixed and floating base
// -----------------------------------------------------------------------------------------------

TEST_CASE("integrate is the exponential map", "[reference][models]") {
  std::mt19937 rng(21);
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    const ReferenceModel& m = c.model;
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng);
    CHECK(relErr(m.integrate(q, v, 0.0), q) < 1e-15);
    // One-parameter subgroup: exp((s + t) v) = exp(s v) exp(t v); the quaternion stays unit.
    const Eigen::VectorXd q1 = m.integrate(m.integrate(q, v, 0.3), v, 0.45);
    const Eigen::VectorXd q2 = m.integrate(q, v, 0.75);
    CHECK(relErr(q1, q2) < 1e-13);
    // The same with tiny steps (series branch of the exponential) and across its threshold.
    const Eigen::VectorXd s1 = m.integrate(m.integrate(q, v, 1e-4), v, 2e-4);
    CHECK(relErr(s1, m.integrate(q, v, 3e-4)) < 1e-14);
    const Eigen::VectorXd s2 = m.integrate(m.integrate(q, v, 3e-4), v, 2e-2);
    CHECK(relErr(s2, m.integrate(q, v, 2.03e-2)) < 1e-14);
    if (m.floatingBase()) {
      CHECK(std::abs(q2.segment<4>(3).norm() - 1.0) < 1e-14);
      // Going back along -v returns to the start.
      CHECK(relErr(m.integrate(q2, v, -0.75), q) < 1e-13);
    }
  }
}

TEST_CASE("frame Jacobians are derivatives of frame poses", "[reference][models]") {
  std::mt19937 rng(22);
  const double h = 1e-6;
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    const ReferenceModel& m = c.model;
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng);
    double worst = 0.0;
    for (const std::string& frame : m.frameNames()) {
      const Eigen::Vector3d point = randomVector(3, rng, 0.2);
      for (bool world : {false, true}) {
        const Eigen::MatrixXd J = m.frameJacobian(q, frame, point, world);
        REQUIRE(J.rows() == 6);
        REQUIRE(J.cols() == m.nv());
        worst = std::max(worst, relErr(J * v, fdPointVelocity(m, q, v, frame, point, world, h)));
      }
      // Local and world-aligned Jacobians differ by the frame rotation.
      const auto P = m.framePose(q, frame);
      const Eigen::MatrixXd Jl = m.frameJacobian(q, frame, point, false);
      const Eigen::MatrixXd Jw = m.frameJacobian(q, frame, point, true);
      CHECK(relErr(Jw.topRows(3), P.R * Jl.topRows(3)) < 1e-14);
      CHECK(relErr(Jw.bottomRows(3), P.R * Jl.bottomRows(3)) < 1e-14);
    }
    CHECK(worst < 1e-8);
  }
}

TEST_CASE("bias accelerations are derivatives of J v", "[reference][models]") {
  std::mt19937 rng(23);
  const double h = 1e-6;
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    const ReferenceModel& m = c.model;
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng);
    const Eigen::VectorXd qp = m.integrate(q, v, h), qm = m.integrate(q, v, -h);
    double worst = 0.0;
    // A subset of frames keeps the run time short: every third frame and the last one.
    for (std::size_t f = 0; f < m.frameNames().size(); ++f) {
      if (f % 3 != 0 && f + 1 != m.frameNames().size()) continue;
      const std::string& frame = m.frameNames()[f];
      const Eigen::Vector3d point = randomVector(3, rng, 0.2);
      for (bool world : {false, true}) {
        const Vector6d fd =
            (m.frameJacobian(qp, frame, point, world) * v - m.frameJacobian(qm, frame, point, world) * v) /
            (2 * h);
        worst = std::max(worst, relErr(m.frameBiasAcceleration(q, v, frame, point, world), fd));
      }
    }
    CHECK(worst < 1e-7);
  }
}

TEST_CASE("mass matrix: symmetric, linear part of RNEA, Jacobian form, kinetic energy",
          "[reference][models]") {
  std::mt19937 rng(24);
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    ReferenceModel m = c.model;
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng),
                          a = randomVector(m.nv(), rng);
    const Eigen::MatrixXd M = m.massMatrix(q);
    REQUIRE(M.rows() == m.nv());
    REQUIRE(M.cols() == m.nv());
    CHECK(relErr(M, M.transpose()) < 1e-14);
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    CHECK(eig.minCoeff() > -1e-12 * (1.0 + eig.maxCoeff()));

    // tau is affine in a with the same M, with gravity.
    CHECK(relErr(m.rnea(q, v, a) - m.rnea(q, v, Eigen::VectorXd::Zero(m.nv())), M * a) < 1e-13);
    CHECK(relErr(m.nonLinearEffects(q, v), m.rnea(q, v, Eigen::VectorXd::Zero(m.nv()))) == 0.0);

    // M = sum over merged bodies of J_b^T I_b J_b (body Jacobian at the body origin, spatial
    // inertia from the inertial parameters): a different algorithm and data path.
    const Eigen::VectorXd phi = m.inertialParameters();
    const std::vector<std::string>& bodies = m.bodyNames();
    REQUIRE(phi.size() == 10 * static_cast<Eigen::Index>(bodies.size()));
    Eigen::MatrixXd Mj = Eigen::MatrixXd::Zero(m.nv(), m.nv());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Eigen::MatrixXd J = m.frameJacobian(q, bodies[b], Eigen::Vector3d::Zero(), false);
      Mj += J.transpose() * spatialInertia(phi.segment<10>(10 * static_cast<Eigen::Index>(b))) * J;
    }
    CHECK(relErr(M, Mj) < 1e-13);

    // Power balance without gravity: d/dt (1/2 v^T M v) = v^T tau(q, v, a) along a motion with
    // velocity v and acceleration a at t = 0.
    m.setGravity(Eigen::Vector3d::Zero());
    const double h = 1e-5;
    const auto energy = [&](const Eigen::VectorXd& qq, const Eigen::VectorXd& vv) {
      return 0.5 * vv.dot(m.massMatrix(qq) * vv);
    };
    const double dT =
        (energy(m.integrate(q, v, h), v + h * a) - energy(m.integrate(q, v, -h), v - h * a)) / (2 * h);
    const double power = v.dot(m.rnea(q, v, a));
    CHECK(std::abs(dT - power) < 1e-7 * (1.0 + std::abs(power) + energy(q, v)));
  }
}

TEST_CASE("velocity terms follow the Lagrange / Euler-Poincare equations", "[reference][models]") {
  // Without gravity, with T(q, v) = 1/2 v^T M(q) v and p = M v (p_base = spatial momentum of the
  // whole system in the root frame):
  //   joints: tau_j = d/dt p_j - dT/dq_j                    (ordinary Lagrange equations)
  //   base:   tau_b = d/dt p_b + xi x* p_b                  (Newton-Euler in the moving root frame)
  // where xi is the base twist and dT/dq_j is taken with the base pose and twist held fixed.
  // This checks the full C(q, v) v, including the gyroscopic terms the power balance cannot see.
  std::mt19937 rng(28);
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    ReferenceModel m = c.model;
    m.setGravity(Eigen::Vector3d::Zero());
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng),
                          a = randomVector(m.nv(), rng);
    const double h = 1e-5;
    const Eigen::VectorXd dp = (m.massMatrix(m.integrate(q, v, h)) * (v + h * a) -
                                m.massMatrix(m.integrate(q, v, -h)) * (v - h * a)) /
                               (2 * h);
    Eigen::VectorXd expected = dp;
    const int first_joint = m.floatingBase() ? 6 : 0;
    for (int k = first_joint; k < m.nv(); ++k) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(m.nv(), k);
      const Eigen::VectorXd qp = m.integrate(q, e, h), qm = m.integrate(q, e, -h);
      expected(k) -= 0.5 * (v.dot(m.massMatrix(qp) * v) - v.dot(m.massMatrix(qm) * v)) / (2 * h);
    }
    if (m.floatingBase()) {
      const Eigen::VectorXd p = m.massMatrix(q) * v;
      const Eigen::Vector3d w = v.head<3>(), vl = v.segment<3>(3);
      const Eigen::Vector3d n = p.head<3>(), f = p.segment<3>(3);
      expected.head<3>() += w.cross(n) + vl.cross(f);
      expected.segment<3>(3) += w.cross(f);
    }
    CHECK(relErr(m.rnea(q, v, a), expected) < 1e-8);
  }
}

TEST_CASE("gravity: potential energy gradient, Jacobian form, base wrench", "[reference][models]") {
  std::mt19937 rng(25);
  const Eigen::Vector3d g(0, 0, -kG);
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    const ReferenceModel& m = c.model;
    REQUIRE(m.gravity() == g);
    const Eigen::VectorXd q = randomConfig(m, rng);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.nv());
    const Eigen::VectorXd N0 = m.nonLinearEffects(q, zero);

    // N(q, 0)_k = dU/dq_k along integrate(q, e_k, +-h), U = -M g^T c.
    const double h = 1e-6;
    const auto U = [&](const Eigen::VectorXd& qq) { return -m.totalMass() * g.dot(m.centerOfMass(qq)); };
    Eigen::VectorXd dU(m.nv());
    for (int k = 0; k < m.nv(); ++k) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(m.nv(), k);
      dU(k) = (U(m.integrate(q, e, h)) - U(m.integrate(q, e, -h))) / (2 * h);
    }
    CHECK(relErr(N0, dU) < 1e-7);

    // Gravity torque as a sum over bodies: tau_g = sum_b J_b(c_b)^T (-m_b g).
    const Eigen::VectorXd phi = m.inertialParameters();
    Eigen::VectorXd tau_g = Eigen::VectorXd::Zero(m.nv());
    for (std::size_t b = 0; b < m.bodyNames().size(); ++b) {
      const double mb = phi(10 * static_cast<Eigen::Index>(b));
      if (mb == 0.0) continue;
      const Eigen::Vector3d cb = phi.segment<3>(10 * static_cast<Eigen::Index>(b) + 1) / mb;
      const Eigen::MatrixXd J = m.frameJacobian(q, m.bodyNames()[b], cb, true);
      tau_g += J.bottomRows(3).transpose() * (-mb * g);
    }
    CHECK(relErr(N0, tau_g) < 1e-13);

    if (m.floatingBase()) {
      // Base wrench holding the whole robot: force -M g, moment about the root origin, root frame.
      const auto root = m.framePose(q, m.frameNames()[0]);
      const Eigen::Vector3d f = root.R.transpose() * (-m.totalMass() * g);
      const Eigen::Vector3d com = root.R.transpose() * (m.centerOfMass(q) - root.p);
      CHECK(relErr(N0.segment<3>(3), f) < 1e-13);
      CHECK(relErr(N0.head<3>(), com.cross(f)) < 1e-13);
    }
  }
}

TEST_CASE("floating-base joint block equals the fixed-base model", "[reference][models]") {
  std::mt19937 rng(26);
  for (const std::string& file : modelFiles()) {
    INFO(file);
    const ReferenceModel fixed = load(file, false), floating = load(file, true);
    REQUIRE(floating.nv() == fixed.nv() + 6);
    REQUIRE(floating.jointNames() == fixed.jointNames());
    const Eigen::VectorXd qj = randomConfig(fixed, rng), vj = randomVector(fixed.nv(), rng),
                          aj = randomVector(fixed.nv(), rng);
    Eigen::VectorXd q = floating.neutral();
    q.tail(fixed.nq()) = qj;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(floating.nv()), a = v;
    v.tail(fixed.nv()) = vj;
    a.tail(fixed.nv()) = aj;
    CHECK(relErr(floating.massMatrix(q).bottomRightCorner(fixed.nv(), fixed.nv()), fixed.massMatrix(qj)) <
          1e-13);
    CHECK(relErr(floating.rnea(q, v, a).tail(fixed.nv()), fixed.rnea(qj, vj, aj)) < 1e-13);
    for (const std::string& frame : fixed.frameNames()) {
      CHECK(relErr(floating.framePose(q, frame).R, fixed.framePose(qj, frame).R) < 1e-14);
      CHECK(relErr(floating.framePose(q, frame).p, fixed.framePose(qj, frame).p) < 1e-14);
    }
  }
}

TEST_CASE("centre of mass and inertial parameters", "[reference][models]") {
  std::mt19937 rng(27);
  for (const Case& c : allCases()) {
    INFO(c.file << (c.floating_base ? " floating" : " fixed"));
    const ReferenceModel& m = c.model;
    const Eigen::VectorXd q = randomConfig(m, rng), v = randomVector(m.nv(), rng);
    const Eigen::VectorXd phi = m.inertialParameters();
    REQUIRE(m.totalMass() > 0.0);

    // Total mass and CoM from the merged-body parameters and the body poses.
    double mass = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (std::size_t b = 0; b < m.bodyNames().size(); ++b) {
      const Eigen::Index i = 10 * static_cast<Eigen::Index>(b);
      const auto P = m.framePose(q, m.bodyNames()[b]);
      mass += phi(i);
      moment += phi(i) * P.p + P.R * phi.segment<3>(i + 1);
      // Rotational inertia about the body origin is positive semi-definite.
      Eigen::Matrix3d I;
      I << phi(i + 4), phi(i + 5), phi(i + 7), phi(i + 5), phi(i + 6), phi(i + 8), phi(i + 7), phi(i + 8),
          phi(i + 9);
      CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues().minCoeff() > -1e-12);
    }
    CHECK(mass == Approx(m.totalMass()).epsilon(1e-14));
    CHECK(relErr(m.centerOfMass(q), moment / mass) < 1e-14);

    // CoM Jacobian against finite differences.
    const double h = 1e-6;
    const Eigen::Vector3d dc =
        (m.centerOfMass(m.integrate(q, v, h)) - m.centerOfMass(m.integrate(q, v, -h))) / (2 * h);
    CHECK(relErr(m.comJacobian(q) * v, dc) < 1e-8);
    // For a floating base, the CoM moves with the base translation (rows 3..5: root axes).
    if (m.floatingBase()) {
      const auto root = m.framePose(q, m.frameNames()[0]);
      CHECK(relErr(m.comJacobian(q).middleCols(3, 3), root.R) < 1e-13);
    }
  }
}
