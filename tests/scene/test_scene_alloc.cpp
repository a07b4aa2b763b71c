// The control cycle of both shipped scenes allocates nothing: 10,000 cycles each (update, solve,
// integrate), with tasks re-weighted, removed, restored, released and added again and contacts removed and added
// again between cycles, counted by a replaced global allocator and, since every source of the
// cycle is compiled into this program with EIGEN_RUNTIME_NO_MALLOC and assertions on, checked by
// Eigen itself.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <new>
#include <string>

#include "counting_allocator.hpp"
#include "loop/solution_integrator.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"

using mrqp::qp::QpStatus;
using mrqp::testing::allocationsIn;

namespace {

mrqp::scene::Scene load(const std::string& name) {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  return mrqp::scene::loadScene(std::string(MRQP_SCENES_DIR) + "/" + name, models);
}

/// Runs `cycles` cycles; every 250 cycles it re-weights a task, every 1000 removes a task and a
/// contact and adds them back. Returns the number of non-optimal solves.
int run(mrqp::scene::Scene& scene, int cycles, const std::string& task, const std::string& contact) {
  auto& p = *scene.problem;
  int task_id = scene.task(task);
  int contact_id = scene.contact(contact);
  const double weight = p.task(task_id).weight();
  const mrqp::problem::ContactDesc contact_desc = p.contact(contact_id);
  int failures = 0;
  for (int k = 0; k < cycles; ++k) {
    if (k % 250 == 125) p.setTaskWeight(task_id, weight * (k % 500 == 125 ? 0.5 : 1.0));
    if (k % 1000 == 500) {
      // Removed and restored, then handed back and added again: both allocation-free.
      p.removeTask(task_id);
      if (!p.restoreTask(task_id)) return -1;
      task_id = p.addTask(p.releaseTask(task_id));
      p.removeContact(contact_id);
      contact_id = p.addContact(contact_desc);
      if (task_id < 0 || contact_id < 0) return -1;
    }
    p.update();
    if (p.solve() != QpStatus::Optimal) {
      ++failures;
      continue;
    }
    mrqp::loop::integrateSolution(p, scene.settings.dt);
  }
  return failures;
}

}  // namespace

TEST_CASE("The counting allocator is in effect", "[scene][realtime]") {
  static void* volatile sink;  // keeps the compiler from eliding the pairs below
  CHECK(allocationsIn([] {
          sink = ::operator new(8);
          ::operator delete(sink);
        }) == 1);
  CHECK(allocationsIn([] {
          sink = std::malloc(64);
          std::free(sink);
        }) == 1);
}

TEST_CASE("10,000 cycles of the JVRC-1 box scene allocate nothing", "[scene][realtime]") {
  auto scene = load("jvrc1_box.yaml");
  run(scene, 10, "box_pose", "left_hand");  // first solves outside the count
  int failures = 0;
  const long n = allocationsIn([&] { failures = run(scene, 10000, "box_pose", "left_hand"); });
  CHECK(n == 0);
  CHECK(failures == 0);
}

TEST_CASE("10,000 cycles of the Panda door scene allocate nothing", "[scene][realtime]") {
  auto scene = load("panda_door.yaml");
  run(scene, 10, "door_angle", "grip_top");
  int failures = 0;
  const long n = allocationsIn([&] { failures = run(scene, 10000, "door_angle", "grip_top"); });
  CHECK(n == 0);
  CHECK(failures == 0);
}

TEST_CASE("Constraints are removed, restored, released and added in place without allocating",
          "[scene][realtime]") {
  auto scene = load("panda_door.yaml");
  auto& p = *scene.problem;
  const int latch = scene.joint_inequalities.at("latch");
  const auto& door = p.entity(p.entityIndex("door"));
  mrqp::problem::JointInequalityDesc d;  // the latch again: −q_door + q_handle ≤ 0.01
  d.terms = 2;
  d.entity = {{p.entityIndex("door"), p.entityIndex("door")}};
  d.joint = {{door.jointIndex("door"), door.jointIndex("handle")}};
  d.coeff = {{-1.0, 1.0}};
  d.upper = 0.01;
  run(scene, 10, "door_angle", "grip_top");
  int id = -1, failures = 0;
  bool restored = false, released_in_place = false;
  const long n = allocationsIn([&] {
    p.removeConstraint(latch);
    restored = p.restoreConstraint(latch) && p.constraintActive(latch);
    p.removeConstraint(latch);
    id = p.addJointInequality(d);  // the rows of the removed latch are free again
    failures = run(scene, 500, "door_angle", "grip_top");
    released_in_place = p.releaseConstraint(id) == nullptr && !p.constraintActive(id);
  });
  CHECK(n == 0);
  CHECK(restored);
  CHECK(id >= 0);
  CHECK(id != latch);
  CHECK(released_in_place);
  CHECK(failures == 0);
}
