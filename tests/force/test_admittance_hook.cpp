// The admittance on the controller's loop (control/force/admittance_hook.hpp), over CAN with the
// emulated F/T sensor reading a virtual wall under the Panda's tool (force_setup.hpp):
//   - direct mode closes the force loop: the wall's force (k × depth, the plant's truth) settles
//     on fᵈ and the tool at fᵈ/k below the wall's plane;
//   - the sensor's axes (panda_link8, rotated against the world) and the tool's weight: the
//     sensed force along n is the wall's; a normal in the task frame's axes works as the same
//     normal in world axes; the opposite normal moves the tool the other way;
//   - each mode's wiring: the target (fᵈ or the QP's previous contact force along n) and the
//     force task (switched on with fᵈ along n, off otherwise);
//   - a stale F/T sensor makes the admittance hold: the reference stops, nothing winds up;
//   - mode and fᵈ changes from the timeline move the commanded velocity continuously;
//   - disabled (mrqp-run --no-force-control): the task keeps its scene references;
//   - a frame_pose task gets the references in its linear rows, its orientation left alone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "force_setup.hpp"
#include "loop/fault_injector.hpp"
#include "loop/timeline.hpp"
#include "problem/tasks/contact_force_task.hpp"

using forcetest::ForceSetup;
using mrqp::force::ForceMode;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string pressText() { return forcetest::dataText("panda_press.yaml"); }

/// The scene with its force_control section replaced.
std::string withSection(const std::string& section, const std::string& timeline = "") {
  const std::string text = pressText();
  return text.substr(0, text.find("force_control:\n")) + "force_control:\n" + section +
         (timeline.empty() ? "" : "timeline:\n" + timeline);
}

/// The tool's height and the world rotations of the tool and sensor frames at the start.
struct StartPose {
  double z = 0.0;
  Eigen::Matrix3d R_tool, R_sensor;
};
StartPose startPose(ForceSetup& s) {
  mrqp::problem::Entity& e = s.sc.problem->entity(0);
  e.update();
  return {e.framePose(e.frameIndex("panda_hand_tcp")).p.z(), e.framePose(e.frameIndex("panda_hand_tcp")).R,
          e.framePose(e.frameIndex("panda_link8")).R};
}

double analogStep(double t, double fc) {
  const double w = 2.0 * kPi * fc * t;
  return 1.0 - std::exp(-w) - 2.0 / std::sqrt(3.0) * std::exp(-w / 2.0) * std::sin(std::sqrt(3.0) * w / 2.0);
}
double largestStepIncrement(double fc, double fs) {
  double m = 0.0;
  for (int k = 1; k < static_cast<int>(fs); ++k)
    m = std::max(m, analogStep(k / fs, fc) - analogStep((k - 1) / fs, fc));
  return m;
}

}  // namespace

TEST_CASE("force: direct mode presses the wall with the user force", "[force][loop]") {
  ForceSetup s(pressText(), "p.yaml");
  const StartPose p0 = startPose(s);
  // The sensor's axes are far from the world's: the rotation matters.
  REQUIRE((p0.R_sensor - Eigen::Matrix3d::Identity()).norm() > 0.5);
  s.plant->height = p0.z - 0.005;  // 5 mm under the tool
  s.plant->stiffness = 4000.0;
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  double searching = 0.0, mean_force = 0.0;
  for (int k = 0; k < 8000; ++k) {
    s.cycle();
    if (k == 400) searching = st.velocity;
    if (k >= 5000) mean_force += s.plant->wallForce() / 3000.0;
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  // Before contact: v = K_I fᵈ along n = −z.
  CHECK(searching == Approx(5e-4 * 10.0).epsilon(1e-3));
  // Settled: the wall's force is fᵈ, the tool fᵈ/k below the wall's plane. The loop moves the
  // tool at these sub-mm/s speeds in steps of about 0.15 mm (the drives' setpoints stick, then
  // jump): the force goes round fᵈ in a limit cycle of about ±0.4 N at k = 4000 N/m.
  CHECK(mean_force == Approx(10.0).margin(0.2));
  CHECK(s.plant->wallForce() == Approx(10.0).margin(0.6));
  CHECK(s.plant->contactHeight() == Approx(s.plant->height - 10.0 / 4000.0).margin(1.5e-4));
  // The sensed force along n is the wall's (through the rotated sensor axes, 0.02 N encoding).
  CHECK(st.measured == Approx(s.plant->wallForce()).margin(0.05));
  CHECK(st.target == 10.0);
  CHECK(st.holds <= 1u);  // the first cycle, before the first sample
  CHECK(st.normal == Eigen::Vector3d(0, 0, -1));
  // The reference moved along n only.
  CHECK(st.displacement.x() == 0.0);
  CHECK(st.displacement.y() == 0.0);
  CHECK(st.displacement.z() == Approx(-0.0075).margin(5e-4));
  CHECK(std::fabs(st.velocity) < 5e-4 * 0.6);
}

TEST_CASE("force: sensor frames and the tool's weight and the normal's sign", "[force][loop]") {
  SECTION("the normal in the task frame's axes acts as the same normal in world axes") {
    ForceSetup probe(pressText(), "p.yaml");
    const StartPose p0 = startPose(probe);
    const Eigen::Vector3d n_tool = p0.R_tool.transpose() * Eigen::Vector3d(0, 0, -1);
    REQUIRE((n_tool - Eigen::Vector3d(0, 0, -1)).norm() > 0.1);  // the tool's axes are not the world's
    std::ostringstream item;
    item.precision(17);
    item << "  - {name: tool, task: press, sensor: panda_link8, normal: [" << n_tool.x() << ", " << n_tool.y()
         << ", " << n_tool.z() << "], normal_frame: task, mode: direct, force: 10}\n";
    ForceSetup s(withSection(item.str()), "p.yaml");
    s.plant->height = p0.z - 0.005;
    REQUIRE(s.boot());
    double mean_force = 0.0;
    for (int k = 0; k < 8000; ++k) {
      s.cycle();
      if (k >= 5000) mean_force += s.plant->wallForce() / 3000.0;
    }
    INFO("n = " << s.hook->state(0).normal.transpose());
    CHECK(s.hook->state(0).normal.isApprox(Eigen::Vector3d(0, 0, -1), 2e-2));  // the tool turns a little
    CHECK(mean_force == Approx(10.0).margin(0.3));
  }
  SECTION("the opposite normal moves the tool away") {
    ForceSetup s(
        withSection("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, 1], normal_frame: "
                    "world, mode: direct, force: 10}\n"),
        "p.yaml");
    s.plant->height = startPose(s).z - 0.005;
    REQUIRE(s.boot());
    for (int k = 0; k < 1000; ++k) s.cycle();
    CHECK(s.hook->state(0).velocity == Approx(5e-4 * 10.0).epsilon(1e-3));
    CHECK(s.hook->state(0).velocity_ref.z() == Approx(5e-4 * 10.0).epsilon(1e-3));
    CHECK(s.hook->state(0).displacement.z() > 0.004);
    CHECK(s.plant->wallForce() == 0.0);
  }
  SECTION("pressing with the opposite normal: the sensed force is negative along it") {
    ForceSetup s(pressText(), "p.yaml");
    s.plant->height = startPose(s).z + 0.002;  // the wall 2 mm into the tool: 8 N at the start
    REQUIRE(s.boot());
    for (int k = 0; k < 9; ++k) s.cycle();  // robot cycles 0, 4, 8: samples
    const double pressing = s.hook->state(0).measured;
    CHECK(pressing == Approx(8.0).margin(0.05));
    ForceSetup t(
        withSection("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, 1], normal_frame: "
                    "world, mode: direct, force: 0}\n"),
        "p.yaml");
    t.plant->height = startPose(t).z + 0.002;
    REQUIRE(t.boot());
    for (int k = 0; k < 9; ++k) t.cycle();
    CHECK(t.hook->state(0).measured == Approx(-pressing).margin(0.05));
  }
  SECTION("the tool's weight is removed") {
    for (const double scene_mass : {0.0, 0.7}) {
      INFO("tool_mass in the scene " << scene_mass);
      ForceSetup s(withSection("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], "
                               "normal_frame: world, mode: direct, force: 10, tool_mass: " +
                               std::to_string(scene_mass) + "}\n"),
                   "p.yaml");
      s.plant->tool_mass = 0.7;  // the sensor carries 0.7 kg of tool; no wall
      REQUIRE(s.boot());
      for (int k = 0; k < 9; ++k) s.cycle();
      // Without the scene's tool mass the weight reads as something pulling the tool down: a
      // negative pressing force along the downward normal, −m g.
      CHECK(s.hook->state(0).measured == Approx(-(0.7 - scene_mass) * 9.81).margin(0.05));
    }
  }
}

TEST_CASE("force: each mode's target and force task", "[force][loop]") {
  // The contact with the table active: the tool is held, the QP computes its force.
  const std::string text = forcetest::replaced(
      withSection(
          "  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], normal_frame: world, "
          "mode: qp, force: 6, force_task: press_force}\n"),
      "active: false", "active: true\n    free: [normal]");
  ForceSetup s(text, "p.yaml");
  mrqp::problem::MultiRobotProblem& p = *s.sc.problem;
  const int contact = s.sc.contact("hand_table");
  const int force_task = s.sc.task("press_force");
  const auto& ftask = dynamic_cast<const mrqp::problem::ContactForceTask&>(p.task(force_task));
  const Eigen::Vector3d n(0, 0, -1);
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  // The force the QP's previous solution applies through the tool (the contact is on the panda:
  // the tool applies the opposite of the force on it).
  Eigen::Vector3d qp_applied = Eigen::Vector3d::Zero();
  auto run = [&](ForceMode mode, int cycles) {
    REQUIRE(s.hook->setMode(0, mode));
    for (int k = 0; k < cycles; ++k) {
      qp_applied = -p.contactForce(contact);
      s.cycle();
      if (k % 4 != 0) continue;  // the robot's cycles (divisor 4)
      INFO(mrqp::force::forceModeName(mode) << ", cycle " << k);
      CHECK(st.mode == mode);
      const double expected_target = mrqp::force::targetFromQp(mode) ? qp_applied.dot(n) : 6.0;
      CHECK(st.target == Approx(expected_target).margin(1e-12));
      CHECK(p.taskActive(force_task) == mrqp::force::forceTaskOn(mode));
      if (mrqp::force::forceTaskOn(mode)) {
        // fᵈ along n; the tangential part as the QP left it.
        const Eigen::Vector3d wanted = -ftask.target();
        CHECK(wanted.dot(n) == Approx(6.0).margin(1e-12));
        CHECK((wanted - wanted.dot(n) * n - (qp_applied - qp_applied.dot(n) * n)).norm() < 1e-12);
      }
    }
  };
  run(ForceMode::Qp, 400);
  // With the force task in the QP, the QP's own force along n goes to fᵈ.
  CHECK(-p.contactForce(contact).dot(n) == Approx(6.0).margin(0.05));
  CHECK(st.target == Approx(6.0).margin(0.05));
  run(ForceMode::Guided, 100);
  run(ForceMode::Autonomous, 400);
  // Without the force task nothing asks for a force: the QP's force along n drops.
  CHECK(std::fabs(-p.contactForce(contact).dot(n)) < 1.0);
  run(ForceMode::Direct, 100);
  run(ForceMode::Off, 400);
  CHECK(st.holding);
  CHECK(std::fabs(st.velocity) < 1e-6);
  REQUIRE_FALSE(s.ctrl->safeStopped());

  // An end-effector without a contact or a force task cannot take the modes that need them.
  ForceSetup d(pressText(), "p.yaml");
  CHECK_FALSE(d.hook->setMode(0, ForceMode::Autonomous));
  CHECK_FALSE(d.hook->setMode(0, ForceMode::Qp));
  CHECK_FALSE(d.hook->setMode(0, ForceMode::Guided));
  CHECK(d.hook->setMode(0, ForceMode::Off));
  CHECK(d.hook->state(0).mode == ForceMode::Off);
  CHECK_FALSE(d.hook->setForce(0, std::nan("")));
}

TEST_CASE("force: a stale F/T sensor makes the admittance hold, not wind up", "[force][loop]") {
  // The controller's own stale-sensor stop far away (1000 robot cycles): the admittance alone.
  const std::string text = forcetest::replaced(
      withSection(
          "  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], normal_frame: world, "
          "mode: direct, force: 500}\n"),
      "hardware:\n", "hardware:\n  feedback_missing_cycles: 1000\n");
  ForceSetup s(text, "p.yaml");  // no wall: searching at v_max
  mrqp::loop::FaultInjector faults({mrqp::loop::parseFaultRequest("stale-ft@1.0")}, s.rig.get(), *s.ctrl,
                                   s.hw);
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  double z_fault = 0.0, z_after = 0.0;
  std::uint64_t holds_before = 0;
  for (int k = 0; k < 3000; ++k) {
    faults.beforeCycle(k * 0.001, s.now);
    s.cycle();
    faults.afterCycle();
    if (k == 999) {
      CHECK(st.velocity == Approx(0.05).epsilon(1e-6));  // v_max along n
      CHECK(st.holds <= 1u);                             // the first cycle, before the first sample
      holds_before = st.holds;
      z_fault = st.displacement.z();
    }
    if (k == 1500) z_after = st.displacement.z();
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  CHECK(st.holding);
  CHECK(st.holds - holds_before > 400u);
  CHECK(st.velocity == 0.0);
  CHECK(st.velocity_ref.norm() == 0.0);
  // The reference stopped within the filter's tail (v_max × 2/ω_c) and a robot cycle or two of
  // detection; then it stays where it is for the rest of the fault.
  CHECK(z_after - z_fault > -(0.05 * 2.0 / (2 * kPi * 20.0) + 0.05 * 0.008));
  CHECK(st.displacement.z() == Approx(z_after).margin(1e-9));
}

TEST_CASE("force: the displacement bound stops a search that finds nothing", "[force][loop]") {
  // No wall: the sensor reads nothing and direct mode searches downwards at v_max; the scene's
  // max_displacement (1 cm) stops the reference there, the task's position reference within
  // 1 cm of its nominal position along n, the command back at rest.
  const std::string text = withSection(
      "  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], normal_frame: world, "
      "mode: direct, force: 500, max_displacement: 0.01}\n");
  ForceSetup s(text, "p.yaml");
  REQUIRE(s.hook->admittance(0).gains().max_displacement == 0.01);
  const Eigen::Vector3d nominal = s.hook->state(0).position_ref;  // the task's target at the start
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  double deepest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    s.cycle();
    deepest = std::max(deepest, nominal.z() - st.position_ref.z());
    if (k == 100) CHECK(st.velocity == Approx(0.05).epsilon(0.01));  // searching at v_max
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  CHECK(deepest <= 0.01 + 1e-12);
  CHECK(nominal.z() - st.position_ref.z() == Approx(0.01).epsilon(2e-3));
  CHECK(st.normal_displacement == Approx(nominal.z() - st.position_ref.z()).margin(1e-12));
  CHECK((st.position_ref.head<2>() - nominal.head<2>()).norm() < 1e-12);
  CHECK(std::fabs(st.velocity) < 1e-5);
}

TEST_CASE("force: mode and force changes from the timeline are bumpless", "[force][loop]") {
  const std::string text = withSection(
      "  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], normal_frame: world, "
      "mode: direct, force: 500}\n",
      "  - {at: 0.5, force_control: tool, force: -500}\n"
      "  - {at: 1.0, force_control: tool, mode: off}\n"
      "  - {at: 1.5, force_control: tool, mode: direct, force: 500}\n");
  ForceSetup s(text, "p.yaml");
  REQUIRE(s.hook->size() == 1);
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  // Each change moves v_c by up to v_max − v_min in one robot cycle; the commanded velocity
  // moves by at most that times the filter's largest step increment, spread over the robot
  // cycle's four loop cycles.
  const double bound = 0.1 * largestStepIncrement(20.0, 250.0) / 4.0 * 1.02;
  double prev = 0.0, largest = 0.0, largest_clamped = 0.0, prev_clamped = 0.0;
  for (int k = 0; k < 2000; ++k) {
    s.cycle();
    const double v = st.velocity_ref.dot(st.normal);
    if (k > 0) {
      largest = std::max(largest, std::fabs(v - prev));
      largest_clamped = std::max(largest_clamped, std::fabs(st.clamped - prev_clamped));
    }
    prev = v;
    prev_clamped = st.clamped;
    if (k == 499) CHECK(v == Approx(0.05).epsilon(1e-6));
    if (k == 999) CHECK(v == Approx(-0.05).epsilon(1e-6));
    if (k == 1499) CHECK(v == Approx(0.0).margin(1e-9));
  }
  CHECK(s.hook->eventsPlayed() == 3);
  CHECK(largest_clamped == Approx(0.1));  // the law itself jumps...
  CHECK(largest <= bound);                // ...the command does not
  CHECK(st.velocity == Approx(0.05).epsilon(1e-4));
  CHECK(st.mode == ForceMode::Direct);
}

TEST_CASE("force: the acceleration and position references are the velocity's", "[force][loop]") {
  ForceSetup s(
      withSection("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], normal_frame: "
                  "world, mode: direct, force: 500}\n",
                  "  - {at: 0.3, task: press, target: [0.5, 0.02, 0.4]}\n"),
      "p.yaml");
  mrqp::loop::Timeline tl = mrqp::loop::Timeline::read(
      withSection("", "  - {at: 0.3, task: press, target: [0.5, 0.02, 0.4]}\n"), "p.yaml", s.sc);
  REQUIRE(s.ctrl->addHook(tl));
  const auto& st = s.hook->state(0);
  const auto& task = dynamic_cast<const mrqp::problem::FrameTask&>(s.sc.problem->task(s.sc.task("press")));
  const Eigen::Vector3d nominal0 = task.target();
  REQUIRE(s.boot());
  Eigen::Vector3d v_prev = Eigen::Vector3d::Zero();
  for (int k = 0; k < 600; ++k) {
    s.cycle();
    INFO("cycle " << k);
    // g̈ʳᵉᶠ is the slope of ġʳᵉᶠ; gʳᵉᶠ − nominal is the sum of ġʳᵉᶠ dt.
    CHECK((st.velocity_ref - v_prev - st.acceleration_ref * 0.001).norm() < 1e-12);
    v_prev = st.velocity_ref;
    CHECK(s.sc.problem->task(s.sc.task("press")).velocityReference().isApprox(st.velocity_ref));
    const Eigen::Vector3d nominal = k < 300 ? nominal0 : Eigen::Vector3d(0.5, 0.02, 0.4);
    // The timeline's new target (played after the admittance in this cycle) becomes the nominal
    // position from the next cycle on.
    if (k != 300) CHECK((task.target() - nominal - st.displacement).norm() < 1e-12);
  }
}

TEST_CASE("force: disabled force control leaves the task's references alone", "[force][loop]") {
  ForceSetup s(forcetest::replaced(
                   withSection("  - {name: tool, task: press, sensor: panda_link8, normal: [0, 0, -1], "
                               "normal_frame: world, mode: qp, force: 6, force_task: press_force}\n",
                               "  - {at: 0.1, force_control: tool, mode: direct}\n"),
                   "active: false", "active: true\n    free: [normal]"),
               "p.yaml", /*disabled=*/true);
  const int force_task = s.sc.task("press_force");
  const auto& task = dynamic_cast<const mrqp::problem::FrameTask&>(s.sc.problem->task(s.sc.task("press")));
  const Eigen::Vector3d nominal = task.target();
  REQUIRE(s.boot());
  for (int k = 0; k < 500; ++k) {
    s.cycle();
    CHECK(s.hook->state(0).mode == ForceMode::Off);
    CHECK_FALSE(s.sc.problem->taskActive(force_task));
  }
  CHECK(task.target() == nominal);
  CHECK(s.sc.problem->task(s.sc.task("press")).velocityReference().norm() == 0.0);
  CHECK(s.sc.problem->task(s.sc.task("press")).accelerationReference().norm() == 0.0);
}

TEST_CASE("force: a frame_pose task gets the references in its linear rows", "[force][loop]") {
  ForceSetup s(forcetest::replaced(pressText(), "type: frame_position", "type: frame_pose"), "p.yaml");
  const int id = s.sc.task("press");
  const auto& task = dynamic_cast<const mrqp::problem::FrameTask&>(s.sc.problem->task(id));
  REQUIRE(std::string(task.kind()) == "frame_pose");
  const Eigen::Vector3d nominal = task.target();
  const Eigen::Matrix3d rotation = task.targetRotation();
  REQUIRE(s.boot());
  const auto& st = s.hook->state(0);
  for (int k = 0; k < 1000; ++k) s.cycle();  // no wall: searching down at K_I fᵈ
  REQUIRE_FALSE(s.ctrl->safeStopped());
  const Eigen::VectorXd& v = s.sc.problem->task(id).velocityReference();
  const Eigen::VectorXd& a = s.sc.problem->task(id).accelerationReference();
  REQUIRE(v.size() == 6);
  CHECK(v.head<3>().norm() == 0.0);  // angular rows: no reference
  CHECK(a.head<3>().norm() == 0.0);
  CHECK(v.tail<3>() == st.velocity_ref);
  CHECK(a.tail<3>() == st.acceleration_ref);
  CHECK(st.velocity_ref.z() == Approx(-5e-4 * 10.0).epsilon(1e-3));
  CHECK((task.target() - nominal - st.displacement).norm() < 1e-12);
  CHECK(st.displacement.z() < -0.004);
  CHECK(task.targetRotation() == rotation);  // the orientation target is left alone
}
