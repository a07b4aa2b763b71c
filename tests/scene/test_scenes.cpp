// The shipped scenes (tools/scenes) run closed loop on their own models: JVRC-1 moves a box held
// in both hands with a task on the box only; a Panda opens a latched door with a task on the door
// angle only. Each cycle is checked against the entities' own equations of motion (action and
// reaction), the exact friction cones and the support polygon.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

#include "loop/solution_integrator.hpp"
#include "problem/constraints/com_damper.hpp"
#include "problem/contact.hpp"
#include "problem/tasks/contact_force_task.hpp"
#include "problem/tasks/force_min_task.hpp"
#include "problem/tasks/frame_pose_task.hpp"
#include "problem/tasks/joint_task.hpp"
#include "problem/tasks/posture_task.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene_checks.hpp"

using mrqp::problem::ComDamper;
using mrqp::problem::ForceMinTask;
using mrqp::problem::FramePoseTask;
using mrqp::problem::JointTask;
using mrqp::problem::PostureTask;
using mrqp::qp::QpStatus;

namespace {

mrqp::scene::Scene load(const std::string& name) {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  return mrqp::scene::loadScene(std::string(MRQP_SCENES_DIR) + "/" + name, models);
}

}  // namespace

TEST_CASE("JVRC-1 carries a box to its target with a task on the box pose only", "[scene]") {
  auto scene = load("jvrc1_box.yaml");
  auto& p = *scene.problem;
  const int jvrc = p.entityIndex("jvrc"), box = p.entityIndex("box");
  REQUIRE(jvrc >= 0);
  REQUIRE(box >= 0);
  // No task on the hands or feet: the box pose, and regularisers (posture, small forces).
  for (const auto& [name, id] : scene.tasks) {
    const auto* pose = dynamic_cast<const FramePoseTask*>(&p.task(id));
    const bool allowed = (pose != nullptr && pose->entity() == box) ||
                         dynamic_cast<const PostureTask*>(&p.task(id)) != nullptr ||
                         dynamic_cast<const ForceMinTask*>(&p.task(id)) != nullptr;
    CHECK(allowed);
  }
  const int task = scene.task("box_pose");
  const int lh = scene.contact("left_hand"), rh = scene.contact("right_hand");
  const auto& box_pose = dynamic_cast<const FramePoseTask&>(p.task(task));
  const Eigen::Vector3d target_p = box_pose.target();
  const Eigen::Matrix3d target_R = box_pose.targetRotation();
  REQUIRE((target_p - p.entity(box).framePose(0).p).norm() > 0.05);

  double worst_eom = 0.0, worst_cone = 0.0, worst_margin = 1.0, worst_pair = 0.0;
  const int cycles = static_cast<int>(std::lround(scene.settings.duration / scene.settings.dt));
  for (int k = 0; k < cycles; ++k) {
    p.update();
    REQUIRE(p.solve() == QpStatus::Optimal);
    worst_eom = std::max(worst_eom, mrqp::testing::eomResidual(p));
    worst_cone = std::max(worst_cone, mrqp::testing::coneViolation(p));
    worst_margin = std::min(
        worst_margin,
        dynamic_cast<const ComDamper&>(p.constraint(0)).polygon().margin(p.entity(jvrc).com().head<2>()));
    // Equal and opposite by construction: the robot's hand gets −w at the very same point, which
    // eomResidual checks against the robot's own dynamics; here the box's net wrench is compared
    // with what its Newton–Euler equation needs.
    const mrqp::problem::Entity& b = p.entity(box);
    Eigen::MatrixXd J(6, 6);
    Eigen::VectorXd gen = Eigen::VectorXd::Zero(6);
    for (int c : {lh, rh}) {
      const auto P = b.framePose(0);
      b.frameJacobian(0, P.R.transpose() * (p.contactPoint(c) - P.p), J);
      gen += J.transpose() * p.contactWrench(c);
    }
    const Eigen::VectorXd need = b.massMatrix() * p.acceleration(box) + b.bias();
    worst_pair = std::max(worst_pair, (gen - need).lpNorm<Eigen::Infinity>());
    mrqp::loop::integrateSolution(p, scene.settings.dt);
  }
  p.update();
  const auto P = p.entity(box).framePose(0);
  const double pos_err = (P.p - target_p).norm();
  const double rot_err = Eigen::AngleAxisd(P.R * target_R.transpose()).angle();
  INFO("box position error " << pos_err << " m, orientation error " << rot_err << " rad");
  INFO("EoM residual " << worst_eom << ", cone violation " << worst_cone << " N, CoM margin " << worst_margin
                       << " m, box wrench mismatch " << worst_pair);
  CHECK(pos_err < 1e-3);
  CHECK(rot_err < 1e-3);
  CHECK(worst_eom < 1e-9);
  CHECK(worst_pair < 1e-9);
  CHECK(worst_cone < 1e-9);
  CHECK(worst_margin > 0.01 - 1e-6);  // the damper's security distance
  // The hands do hold it: the vertical forces carry the box's weight.
  CHECK(p.contactForce(lh).z() + p.contactForce(rh).z() == Approx(2.0 * 9.81).epsilon(1e-3));
}

TEST_CASE("A Panda opens a latched door with a task on the door angle only", "[scene]") {
  auto scene = load("panda_door.yaml");
  auto& p = *scene.problem;
  const int panda = p.entityIndex("panda"), door = p.entityIndex("door");
  for (const auto& [name, id] : scene.tasks) {
    const auto* joint = dynamic_cast<const JointTask*>(&p.task(id));
    const auto* posture = dynamic_cast<const PostureTask*>(&p.task(id));
    const bool allowed = (joint != nullptr && joint->entity() == door) ||
                         (posture != nullptr && posture->entity() == panda) ||
                         dynamic_cast<const ForceMinTask*>(&p.task(id)) != nullptr;
    CHECK(allowed);
  }
  const auto& d = p.entity(door);
  const int hinge = d.jointIndex("door"), handle = d.jointIndex("handle");
  const double target = dynamic_cast<const JointTask&>(p.task(scene.task("door_angle"))).target();
  REQUIRE(target < -0.1);
  // The spring of the handle comes from the scene file.
  CHECK(d.springs()[static_cast<std::size_t>(handle)].stiffness == 2.0);
  double min_handle = 0.0, worst_latch = -1.0, worst_eom = 0.0, worst_cone = 0.0, max_door_tau = 0.0;
  const int cycles = static_cast<int>(std::lround(scene.settings.duration / scene.settings.dt));
  for (int k = 0; k < cycles; ++k) {
    p.update();
    REQUIRE(p.solve() == QpStatus::Optimal);
    worst_eom = std::max(worst_eom, mrqp::testing::eomResidual(p));
    worst_cone = std::max(worst_cone, mrqp::testing::coneViolation(p));
    max_door_tau = std::max(max_door_tau, p.torque(door).lpNorm<Eigen::Infinity>());
    mrqp::loop::integrateSolution(p, scene.settings.dt);
    const double qd = d.q()(hinge), qh = d.q()(handle);
    min_handle = std::min(min_handle, qh);
    worst_latch = std::max(worst_latch, -qd + qh - 0.01);  // latch: −q_door + q_handle ≤ 0.01
  }
  INFO("door " << d.q()(hinge) << " rad (target " << target << "), handle min " << min_handle << ", latch "
               << worst_latch << ", EoM " << worst_eom << ", cone " << worst_cone);
  CHECK(std::abs(d.q()(hinge) - target) < 5e-3);
  CHECK(min_handle < target + 0.01);  // the handle was turned as far as the latch needs
  CHECK(worst_latch < 1e-3);
  CHECK(worst_eom < 1e-9);
  CHECK(worst_cone < 1e-9);
  CHECK(max_door_tau == 0.0);  // a passive mechanism: moved only by the contact forces
}

TEST_CASE("A QP force task sets the squeeze on the box that the dynamics leave free", "[scene]") {
  auto scene = load("jvrc1_box.yaml");
  auto& p = *scene.problem;
  const int lh = scene.contact("left_hand"), rh = scene.contact("right_hand");
  // The hands' squeeze is an internal force: the box's motion does not fix it. Ask for 30 N on
  // the left face along y only (the force on the box points into it, −y).
  auto t = std::make_unique<mrqp::problem::ContactForceTask>(lh, Eigen::Vector3d(0.0, -30.0, 0.0));
  t->setWeight(10.0);
  t->setSelection({{0, 1, 0, 0, 0, 0}});
  REQUIRE(p.addTask(std::move(t)) >= 0);
  for (int k = 0; k < 200; ++k) {
    p.update();
    REQUIRE(p.solve() == QpStatus::Optimal);
    mrqp::loop::integrateSolution(p, scene.settings.dt);
  }
  CHECK(p.contactForce(lh).y() == Approx(-30.0).epsilon(1e-3));
  CHECK(p.contactForce(rh).y() == Approx(30.0).epsilon(1e-2));  // the other hand balances it
  CHECK(mrqp::testing::coneViolation(p) < 1e-9);
}
