// Contacts with free directions (problem/contact.hpp, ContactDesc::free): the no-slip rows of the
// held directions only, checked against references that do not use the projection:
//   - the assembled rows with a free normal equal the rows of the same contact held in all six
//     directions (world rows, the path of a contact without free directions) rotated into the
//     contact frame, minus the normal's row; and equal a slow reference built here from the
//     entities' Jacobians, J̇v and the drift terms;
//   - a QP in which a task moves the free direction: the body accelerates along the normal by the
//     projection n nᵀ a_des of the task's desired acceleration (closed form of the least-squares
//     task with one free direction), its held directions at zero relative acceleration; the same
//     contact held in all directions keeps it still;
//   - contactFrame is the basis of the cone generators; the rules on the free bits.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <vector>

#include "cube_contacts.hpp"
#include "problem/contact.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/rigid_object.hpp"
#include "problem/tasks/frame_position_task.hpp"

using namespace mrqp::problem;
using mrqp::qp::QpStatus;
using problemtest::contactProblemSettings;
using problemtest::cube;
using problemtest::squareContact;

namespace {

ContactDesc square(int entity, double half, double z, const Eigen::Vector3d& normal) {
  ContactDesc c = squareContact(entity, half, z);
  c.normal = normal;
  c.friction = 1.0;
  c.generators = 4;
  return c;
}

ProblemSettings settings() {
  ProblemSettings s = contactProblemSettings();
  s.regularisation = 1e-8;
  return s;
}

/// Two cubes: b stacked on a; contact 0: a on the ground, contact 1: b on a (reaction on a).
/// Both with the given free bits and a tilted normal. After establishing, the state is moved
/// and given velocities, so that the drift and bias terms are not zero.
std::unique_ptr<MultiRobotProblem> stack(std::uint8_t free) {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(cube("a", 2.0, {0.0, 0.0, 0.05}));
  es.push_back(cube("b", 1.0, {0.01, -0.02, 0.15}));
  auto p = std::make_unique<MultiRobotProblem>(std::move(es), settings());
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.3, 1.0).normalized();
  ContactDesc ground = square(0, 0.05, -0.05, n);
  ground.free = free;
  ContactDesc on_a = square(1, 0.05, -0.05, n);
  on_a.other_entity = 0;
  on_a.other_frame = 0;
  on_a.free = free;
  REQUIRE(p->addContact(ground) == 0);
  REQUIRE(p->addContact(on_a) == 1);
  REQUIRE(p->update() == UpdateStatus::Ok);  // establishes both
  // Move and spin both bodies (quaternion of a small rotation, body twists).
  const Eigen::Quaterniond qa(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Quaterniond qb(Eigen::AngleAxisd(-0.04, Eigen::Vector3d(-2, 1, 1).normalized()));
  Entity& a = p->entity(0);
  Entity& b = p->entity(1);
  a.q().head<3>() += Eigen::Vector3d(0.003, -0.002, 0.004);
  a.q().segment<4>(3) << qa.w(), qa.x(), qa.y(), qa.z();
  b.q().head<3>() += Eigen::Vector3d(-0.002, 0.005, 0.001);
  b.q().segment<4>(3) << qb.w(), qb.x(), qb.y(), qb.z();
  a.v() << 0.3, -0.2, 0.1, 0.05, 0.02, -0.04;
  b.v() << -0.1, 0.4, 0.2, -0.03, 0.06, 0.01;
  REQUIRE(p->update() == UpdateStatus::Ok);
  return p;
}

Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace

TEST_CASE("contactFrame is the orthonormal basis (t1, t2, n) of the cone generators", "[problem]") {
  for (const Eigen::Vector3d& n :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(Eigen::Vector3d(1, 2, -3).normalized()),
        Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0)}) {
    const Eigen::Matrix3d F = contactFrame(n);
    CHECK((F.transpose() * F - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    CHECK(F.determinant() == Approx(1.0));
    CHECK((F.col(2) - n).norm() < 1e-15);
    // Generator 0 leans toward t1, generator K/4 toward t2.
    const Eigen::Vector3d g0 = coneGenerator(n, 0.5, 0, 4), g1 = coneGenerator(n, 0.5, 1, 4);
    CHECK(((n + 0.5 * F.col(0)).normalized() - g0).norm() < 1e-12);
    CHECK(((n + 0.5 * F.col(1)).normalized() - g1).norm() < 1e-12);
  }
}

TEST_CASE("Free directions: row counts and the rules", "[problem]") {
  ContactDesc c = square(0, 0.05, 0.0, Eigen::Vector3d::UnitZ());
  c.entity = 0;
  c.frame = 0;
  CHECK(c.rows() == 6);
  c.free = kFreeNormal;
  CHECK(c.rows() == 5);
  c.free = kFreeNormal | kFreeTwist | kFreeTangent;
  CHECK(c.rows() == 2);
  CHECK(validateContact(c) == nullptr);
  c.free = 0x40;
  CHECK(validateContact(c) != nullptr);
  ContactDesc point = c;
  point.npoints = 1;
  point.free = kFreeNormal;
  CHECK(point.rows() == 2);
  CHECK(validateContact(point) == nullptr);
  point.free = kFreeTwist;
  REQUIRE(validateContact(point) != nullptr);
  CHECK(std::string(validateContact(point)).find("point contact") != std::string::npos);
}

TEST_CASE("A free normal drops exactly the normal's row of the no-slip constraint", "[problem]") {
  auto held = stack(0);
  auto freed = stack(kFreeNormal);
  const MultiRobotProblem& ph = *held;
  const MultiRobotProblem& pf = *freed;
  // Rows: 12 unactuated (two floating bodies), then contact 0, then contact 1.
  REQUIRE(ph.qp().me() == 12 + 6 + 6);
  REQUIRE(pf.qp().me() == 12 + 5 + 5);
  const int nv = ph.totalVelocities();
  REQUIRE(pf.qp().n() == ph.qp().n());
  const Eigen::MatrixXd Ah = ph.qp().A(), Af = pf.qp().A();
  const Eigen::VectorXd bh = ph.qp().b(), bf = pf.qp().b();
  // The EoM rows are the same.
  CHECK((Ah.topRows(12) - Af.topRows(12)).norm() < 1e-12);
  CHECK((bh.head(12) - bf.head(12)).norm() < 1e-12);

  for (int c = 0; c < 2; ++c) {
    const Entity& e = pf.entity(c);
    const Pose sf = e.framePose(0);
    const Eigen::Matrix3d Rc = sf.R * contactFrame(pf.contact(c).normal);
    // (1) The full rows (world, angular first) rotated into the contact frame (translations
    // first), the normal's translation (row 2) dropped.
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Zero();
    T.block<3, 3>(0, 3) = Rc.transpose();
    T.block<3, 3>(3, 0) = Rc.transpose();
    const Eigen::MatrixXd full = T * Ah.middleRows(12 + 6 * c, 6).leftCols(nv);
    const Eigen::VectorXd full_b = T * bh.segment(12 + 6 * c, 6);
    Eigen::MatrixXd expect(5, nv);
    Eigen::VectorXd expect_b(5);
    expect << full.topRows(2), full.bottomRows(3);
    expect_b << full_b.head(2), full_b.tail(3);
    const Eigen::MatrixXd got = Af.middleRows(12 + 5 * c, 5).leftCols(nv);
    const Eigen::VectorXd got_b = bf.segment(12 + 5 * c, 5);
    CHECK((got - expect).norm() < 1e-12 * (1.0 + expect.norm()));
    CHECK((got_b - expect_b).norm() < 1e-12 * (1.0 + expect_b.norm()));
    // No λ column in the no-slip rows.
    CHECK(Af.middleRows(12 + 5 * c, 5).rightCols(pf.qp().n() - nv).norm() == 0.0);

    // (2) A slow reference from the Jacobians: the relative acceleration of the contact centroid
    // (this contact's entity minus the other's, or minus the ground), rows (t1, t2; ω about t1,
    // t2, n), equal to −J̇v − Kp e − Kd ė with e from the poses at establishment.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) centroid += pf.contact(c).points[static_cast<std::size_t>(k)] / 4.0;
    Eigen::MatrixXd Jrel = Eigen::MatrixXd::Zero(6, nv);
    Eigen::MatrixXd Ja(6, 6);
    e.frameJacobian(0, centroid, Ja);
    Jrel.middleCols(pf.velocityOffset(c), 6) = Ja;
    Vector6d bias = e.frameBiasAcceleration(0, centroid);
    Vector6d vel = Ja * e.v();
    const Eigen::Vector3d cw = sf.R * centroid + sf.p;
    Vector6d err;
    // The targets frozen at establishment: the first update() of stack(), before the move
    // (poses of a body at its initial q: identity rotation, translation as given).
    const Eigen::Vector3d p0a(0.0, 0.0, 0.05), p0b(0.01, -0.02, 0.15);
    if (c == 0) {
      err.head<3>() = rotationVector(sf.R);
      err.tail<3>() = cw - (p0a + centroid);
    } else {
      const Entity& o = pf.entity(0);
      const Pose of = o.framePose(0);
      const Eigen::Vector3d cb = of.R.transpose() * (cw - of.p);
      Eigen::MatrixXd Jb(6, 6);
      o.frameJacobian(0, cb, Jb);
      Jrel.middleCols(pf.velocityOffset(0), 6) -= Jb;
      bias -= o.frameBiasAcceleration(0, cb);
      vel -= Jb * o.v();
      err.head<3>() = rotationVector(sf.R * of.R.transpose());  // both started unrotated
      err.tail<3>() = cw - (of.R * (p0b + centroid - p0a) + of.p);
    }
    const Vector6d rhs = -bias - 100.0 * err - 20.0 * vel;  // default contact gains
    Eigen::MatrixXd ref(5, nv);
    Eigen::VectorXd ref_b(5);
    ref.row(0) = Rc.col(0).transpose() * Jrel.bottomRows(3);
    ref.row(1) = Rc.col(1).transpose() * Jrel.bottomRows(3);
    ref_b(0) = Rc.col(0).dot(rhs.tail<3>());
    ref_b(1) = Rc.col(1).dot(rhs.tail<3>());
    for (int k = 0; k < 3; ++k) {
      ref.row(2 + k) = Rc.col(k).transpose() * Jrel.topRows(3);
      ref_b(2 + k) = Rc.col(k).dot(rhs.head<3>());
    }
    CHECK((got - ref).norm() < 1e-10 * (1.0 + ref.norm()));
    CHECK((got_b - ref_b).norm() < 1e-9 * (1.0 + ref_b.norm()));
    // The references are not trivially zero.
    CHECK(ref_b.norm() > 1e-3);
  }
}

TEST_CASE("A task moves a body along its contact's free normal; the held directions stay", "[problem]") {
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, 0.6, 0.8);
  for (const std::uint8_t free : {std::uint8_t{0}, kFreeNormal}) {
    std::vector<std::unique_ptr<Entity>> es;
    es.push_back(cube("box", 2.0, {0.0, 0.0, 0.05}));
    MultiRobotProblem p(std::move(es), settings());
    ContactDesc c = square(0, 0.05, -0.05, n);
    c.free = free;
    c.generators = 8;
    REQUIRE(p.addContact(c) == 0);
    REQUIRE(p.update() == UpdateStatus::Ok);
    // A position task of the box's origin, 10 cm above: desired acceleration K × 0.1 m up.
    const double K = 100.0;
    auto t = std::make_unique<FramePositionTask>(0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.15));
    REQUIRE(t->setGains(K, -1.0));
    REQUIRE(p.addTask(std::move(t)) >= 0);
    REQUIRE(p.update() == UpdateStatus::Ok);
    REQUIRE(p.solve() == QpStatus::Optimal);
    Eigen::MatrixXd J(6, 6);
    p.entity(0).frameJacobian(0, Eigen::Vector3d(0, 0, -0.05), J);  // the contact's centroid
    const Vector6d a = J * p.acceleration(0);                       // v = 0: no bias
    const Eigen::Vector3d a_des(0, 0, K * 0.1);
    if (free == 0) {
      CHECK(a.norm() < 1e-8);
    } else {
      // Least squares over the one free direction: the projection of a_des on n.
      CHECK((a.tail<3>() - n * n.dot(a_des)).norm() < 1e-6);
      CHECK(a.head<3>().norm() < 1e-8);  // no rotation
      // The held translations (t1, t2) at zero relative acceleration.
      const Eigen::Matrix3d F = contactFrame(n);
      CHECK(std::fabs(F.col(0).dot(a.tail<3>())) < 1e-8);
      CHECK(std::fabs(F.col(1).dot(a.tail<3>())) < 1e-8);
      // The contact's force still balances the box: f = m (a − g).
      const Eigen::Vector3d f = p.contactForce(0);
      CHECK((f - 2.0 * (a.tail<3>() - Eigen::Vector3d(0, 0, -9.81))).norm() < 1e-5);
    }
  }
}
