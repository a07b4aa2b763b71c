// Real time: the problem with contacts that leave directions free (problem/contact.hpp) assembles
// and solves 10,000 cycles without a heap allocation (the counting allocator, and Eigen's run-time
// check armed inside the problem's and the QP's libraries built for it).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "counting_allocator.hpp"
#include "cube_contacts.hpp"
#include "problem/contact.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/rigid_object.hpp"
#include "problem/tasks/frame_position_task.hpp"

using namespace mrqp::problem;

TEST_CASE("Contacts with free directions: update and solve allocate nothing", "[problem][realtime]") {
  std::vector<std::unique_ptr<Entity>> es;
  for (int i = 0; i < 2; ++i) {
    auto e = std::make_unique<RigidObject>(i == 0 ? "a" : "b", 1.0 + i, Eigen::Vector3d::Zero(),
                                           Eigen::Matrix3d::Identity() * 0.01);
    e->q()(2) = 0.05 + 0.1 * i;
    es.push_back(std::move(e));
  }
  MultiRobotProblem p(std::move(es), problemtest::contactProblemSettings());
  // a on the ground, free along its normal; b on a as a point contact free in the tangent plane,
  // plus a surface contact of b on a free to twist and along the normal.
  ContactDesc ground = problemtest::squareContact(0, 0.05, -0.05);
  ground.free = kFreeNormal;
  ContactDesc on_a = ground;
  on_a.entity = 1;
  on_a.other_entity = 0;
  on_a.other_frame = 0;
  on_a.free = kFreeNormal | kFreeTwist;
  REQUIRE(p.addContact(ground) >= 0);
  REQUIRE(p.addContact(on_a) >= 0);
  REQUIRE(p.addTask(std::make_unique<FramePositionTask>(0, 0, Eigen::Vector3d::Zero(),
                                                        Eigen::Vector3d(0, 0, 0.1))) >= 0);
  REQUIRE(p.update() == UpdateStatus::Ok);
  REQUIRE(p.qp().me() == 12 + 5 + 4);
  int optimal = 0;
  const long allocations = mrqp::testing::allocationsIn([&] {
    for (int k = 0; k < 10000; ++k) {
      const double t = 1e-3 * k;
      p.entity(0).v()(5) = 0.01 * std::sin(t);
      p.entity(1).v()(2) = 0.02 * std::cos(t);
      if (p.update() != UpdateStatus::Ok) break;
      optimal += p.solve() == mrqp::qp::QpStatus::Optimal ? 1 : 0;
    }
  });
  CHECK(allocations == 0);
  CHECK(optimal == 10000);
}
