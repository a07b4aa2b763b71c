// The problem assembly on small cases with closed-form answers: cone generators, the support
// polygon, a body in free fall, a body resting on the ground, two bodies stacked (action and
// reaction through the bodies' own equations of motion), and input errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "cube_contacts.hpp"
#include "loop/solution_integrator.hpp"
#include "problem/contact.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/rigid_object.hpp"
#include "problem/support_polygon.hpp"
#include "problem/tasks/com_task.hpp"
#include "problem/tasks/frame_position_task.hpp"
#include "scene_checks.hpp"

using namespace mrqp::problem;
using mrqp::qp::QpStatus;
using problemtest::cube;
using problemtest::squareContact;

namespace {

ContactDesc square(int entity, double half, double z) {
  ContactDesc c = squareContact(entity, half, z);
  c.friction = 0.5;
  return c;
}

}  // namespace

TEST_CASE("Cone generators lie on the Coulomb cone, evenly around the normal", "[problem]") {
  for (const Eigen::Vector3d& n :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(Eigen::Vector3d(1, 2, -3).normalized()),
        Eigen::Vector3d(1, 0, 0)}) {
    for (double mu : {0.3, 1.0}) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = 0; k < 6; ++k) {
        const Eigen::Vector3d g = coneGenerator(n, mu, k, 6);
        CHECK(g.norm() == Approx(1.0));
        const double fn = g.dot(n), ft = (g - fn * n).norm();
        CHECK(ft == Approx(mu * fn));
        sum += g;
      }
      CHECK((sum.normalized() - n).norm() < 1e-12);  // symmetric around n
    }
  }
}

TEST_CASE("The support polygon is the convex hull with inward half-planes", "[problem]") {
  SupportPolygon poly;
  for (double x : {-1.0, 1.0}) {
    for (double y : {-2.0, 2.0}) poly.add({x, y, 0.0});
  }
  poly.add({0.2, 0.3, 0.0});  // interior
  poly.add({1.0, 0.0, 0.0});  // on an edge
  poly.build();
  REQUIRE(poly.edges() == 4);
  CHECK(poly.margin({0.0, 0.0}) == Approx(1.0));
  CHECK(poly.margin({0.5, 1.9}) == Approx(0.1));
  CHECK(poly.margin({1.5, 0.0}) == Approx(-0.5));
  SupportPolygon line;
  line.add({0, 0, 0});
  line.add({1, 0, 0});
  line.add({2, 0, 0});
  line.build();
  CHECK(line.edges() == 0);
}

TEST_CASE("A free body falls with g", "[problem]") {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(cube("a", 2.0, {0.0, 0.0, 1.0}, {0.01, 0.02, -0.03}));
  es[0]->v() << 0.3, -0.2, 0.1, 0.5, 0.0, -1.0;  // spinning while it falls
  MultiRobotProblem p(std::move(es), ProblemSettings{});
  p.update();
  REQUIRE(p.solve() == QpStatus::Optimal);
  const Entity& e = p.entity(0);
  const Eigen::Vector3d a = e.comJacobian() * p.acceleration(0) + e.comBias();
  CHECK((a - Eigen::Vector3d(0, 0, -9.81)).norm() < 1e-6);
}

TEST_CASE("A body resting on the ground is carried by a force m·g through its CoM", "[problem]") {
  std::vector<std::unique_ptr<Entity>> es;
  const Eigen::Vector3d com(0.02, -0.01, 0.0);
  es.push_back(cube("a", 3.0, {0.0, 0.0, 0.05}, com));
  MultiRobotProblem p(std::move(es), ProblemSettings{});
  const int c = p.addContact(square(0, 0.05, -0.05));
  REQUIRE(c >= 0);
  p.update();
  REQUIRE(p.solve() == QpStatus::Optimal);
  CHECK(p.acceleration(0).norm() < 1e-6);
  const Vector6d w = p.contactWrench(c);
  CHECK((w.tail<3>() - Eigen::Vector3d(0, 0, 3.0 * 9.81)).norm() < 1e-6);
  // Moment about the contact centroid balances gravity acting at the CoM.
  const Eigen::Vector3d r = p.entity(0).com() - p.contactPoint(c);
  CHECK((w.head<3>() - r.cross(w.tail<3>())).norm() < 1e-6);
  CHECK(p.lambda(c).minCoeff() >= 0.0);
  CHECK(mrqp::testing::eomResidual(p) < 1e-9);
}

TEST_CASE("Two stacked bodies: the reaction is the action's opposite in both EoMs", "[problem]") {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(cube("bottom", 3.0, {0.0, 0.0, 0.05}));
  es.push_back(cube("top", 1.5, {0.0, 0.0, 0.15}));
  MultiRobotProblem p(std::move(es), ProblemSettings{});
  const int ground = p.addContact(square(0, 0.05, -0.05));
  ContactDesc between = square(1, 0.04, -0.05);  // the top body's lower face on the bottom body
  between.other_entity = 0;
  between.other_frame = 0;
  const int mid = p.addContact(between);
  REQUIRE(ground >= 0);
  REQUIRE(mid >= 0);
  for (int k = 0; k < 100; ++k) {
    p.update();
    REQUIRE(p.solve() == QpStatus::Optimal);
    CHECK(mrqp::testing::eomResidual(p) < 1e-9);
    CHECK(mrqp::testing::coneViolation(p) < 1e-9);
    mrqp::loop::integrateSolution(p, 0.001);
  }
  CHECK((p.contactForce(mid) - Eigen::Vector3d(0, 0, 1.5 * 9.81)).norm() < 1e-6);
  CHECK((p.contactForce(ground) - Eigen::Vector3d(0, 0, 4.5 * 9.81)).norm() < 1e-6);
  CHECK(std::abs(p.entity(1).q()(2) - 0.15) < 1e-6);  // no drift of the stack
}

TEST_CASE("Contacts and tasks are added, removed and refused with a reason", "[problem]") {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(cube("a", 1.0, {0.0, 0.0, 0.05}));
  ProblemSettings s;
  s.max_contacts = 1;
  s.max_tasks = 1;
  MultiRobotProblem p(std::move(es), s);
  ContactDesc line = square(0, 0.05, -0.05);
  line.npoints = 2;  // two points: a line, not a surface
  CHECK(p.addContact(line) == -1);
  CHECK(std::string(p.lastError()).find("3 points") != std::string::npos);
  ContactDesc bad = square(0, 0.05, -0.05);
  bad.frame = 7;
  CHECK(p.addContact(bad) == -1);
  const int c = p.addContact(square(0, 0.05, -0.05));
  CHECK(c == 0);
  CHECK(p.addContact(square(0, 0.05, -0.05)) == -1);  // capacity
  CHECK(p.removeContact(c));
  CHECK(p.addContact(square(0, 0.05, -0.05)) == 0);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  CHECK(p.addTask(std::make_unique<FramePositionTask>(0, 3, zero, zero)) == -1);  // no frame 3
  CHECK(std::string(p.lastError()).find("frame") != std::string::npos);
  CHECK(p.addTask(nullptr) == -1);
  auto bad_weight = std::make_unique<FramePositionTask>(0, 0, zero, zero);
  CHECK_FALSE(bad_weight->setWeight(-1.0));
  CHECK(bad_weight->weight() == 1.0);
  const int id = p.addTask(std::make_unique<FramePositionTask>(0, 0, zero, zero));
  CHECK(id == 0);
  CHECK(p.setTaskWeight(id, 5.0));
  CHECK(p.task(id).weight() == 5.0);
  CHECK_FALSE(p.setTaskWeight(id, std::nan("")));
  CHECK(p.addTask(std::make_unique<FramePositionTask>(0, 0, zero, zero)) == -1);  // capacity
  // Removing parks the object: restored under the same id; released, its slot is free again.
  CHECK(p.removeTask(id));
  CHECK_FALSE(p.taskActive(id));
  CHECK_FALSE(p.setTaskWeight(id, 2.0));
  CHECK(p.restoreTask(id));
  CHECK(p.taskActive(id));
  CHECK(p.task(id).weight() == 5.0);
  std::unique_ptr<Task> back = p.releaseTask(id);
  REQUIRE(back != nullptr);
  CHECK_FALSE(p.taskActive(id));
  CHECK(p.addTask(std::move(back)) == id);
}

TEST_CASE("A group CoM task measures the mass-weighted CoM of its entities", "[problem]") {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(cube("a", 1.0, {0.0, 0.0, 0.0}));
  es.push_back(cube("b", 3.0, {0.0, 0.0, 0.0}));
  es[1]->q()(0) = 2.0;
  MultiRobotProblem p(std::move(es), ProblemSettings{});
  const int id = p.addTask(std::make_unique<ComTask>(0b11u, Eigen::Vector3d(1.0, 0.0, 0.0)));
  REQUIRE(id >= 0);
  p.update();
  CHECK((p.taskError(id).head<3>() - Eigen::Vector3d(0.5, 0.0, 0.0)).norm() < 1e-12);  // (0·1 + 2·3)/4 − 1
  // no such entity
  CHECK(p.addTask(std::make_unique<ComTask>(0b100u, Eigen::Vector3d(1.0, 0.0, 0.0))) == -1);
}
