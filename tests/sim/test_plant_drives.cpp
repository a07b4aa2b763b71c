// The plant section's drive model and start (docs/mujoco.md, "Drives", "Settling"): a position
// servo without integral action sags under gravity by the closed form τ_g / kp, with it ends at
// its reference; settling starts the world at rest with every actuated joint where the scene
// puts it and a floating base standing on its soles; the interpolated reference ramps between
// cyclic setpoints; a `replace` shape stands for a link's own geometry; the new keys' errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "scene/scene_yaml.hpp"
#include "sim_scenes.hpp"

using mrqp::sim::testing::makePlant;

namespace {

const char* kArm = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0.5]}
    q: {panda_joint2: 0.6, panda_joint4: -1.2, panda_joint6: 1.8, panda_finger_joint1: 0.02}
)";

/// Holds every joint of the Panda at its scene value with a stiff servo; returns the handles.
std::vector<int> holdPanda(mrqp::sim::MujocoPlant& plant, double kp, double kd) {
  const std::unique_ptr<mrqp::problem::Entity> model = mrqp::sim::testing::registry().make("panda", "panda");
  const int e = plant.entityHandle("panda");
  Eigen::VectorXd q(plant.entityNq(e)), v(plant.entityNv(e));
  plant.entityState(e, q, v);
  std::vector<int> handles;
  for (int k = 0; k < model->nv(); ++k) {
    mrqp::loop::ServoCommand c;
    c.enabled = true;
    c.position = q(k);
    c.kp = kp;
    c.kd = kd;
    const int h = plant.jointHandle("panda", model->jointName(k));
    plant.setServo(h, c);
    handles.push_back(h);
  }
  return handles;
}

}  // namespace

TEST_CASE("MuJoCo plant: a P servo sags by τ_g / kp, integral action removes the sag", "[sim]") {
  const double kp = 5000.0, kd = 100.0;
  // Without integral action: the static error of each joint is its gravity torque over kp
  // (MuJoCo's bias force at rest is the gravity torque).
  auto plain = makePlant(std::string(kArm) + "plant: {timestep: 0.0005}\n");
  const int e = plain->entityHandle("panda");
  Eigen::VectorXd q0(plain->entityNq(e)), v0(plain->entityNv(e));
  plain->entityState(e, q0, v0);
  std::vector<int> h = holdPanda(*plain, kp, kd);
  for (int i = 0; i < 3000; ++i) plain->step(0.001);
  double largest_sag = 0.0;
  for (std::size_t k = 0; k < 7; ++k) {
    const double sag = plain->jointPosition(h[k]) - q0(static_cast<Eigen::Index>(k));
    const double tau_g = plain->data()->qfrc_bias[plain->jointDof(h[k])];
    INFO("joint " << k + 1 << ": sag " << sag << ", gravity torque " << tau_g);
    CHECK(sag == Approx(-tau_g / kp).margin(1e-3 * std::abs(tau_g / kp) + 1e-7));
    largest_sag = std::max(largest_sag, std::abs(sag));
  }
  CHECK(largest_sag > 1e-3);  // the arm is loaded: the comparison means something

  // With integral action (Ti = 0.1 s): at rest on its reference, the torque the gravity's.
  auto integral = makePlant(std::string(kArm) + "plant: {timestep: 0.0005, drives: {integral_time: 0.1}}\n");
  h = holdPanda(*integral, kp, kd);
  for (int i = 0; i < 3000; ++i) integral->step(0.001);
  for (std::size_t k = 0; k < 7; ++k) {
    INFO("joint " << k + 1);
    CHECK(std::abs(integral->jointPosition(h[k]) - q0(static_cast<Eigen::Index>(k))) < 1e-6);
    CHECK(integral->jointTorque(h[k]) ==
          Approx(integral->data()->qfrc_bias[integral->jointDof(h[k])]).margin(1e-3));
  }
}

TEST_CASE("MuJoCo plant: settling starts the arm at rest at its scene values, t = 0", "[sim]") {
  auto plant = makePlant(std::string(kArm) +
                         "plant: {timestep: 0.0005, settle: 1.0, drives: {integral_time: 0.05}}\n");
  auto reference = makePlant(std::string(kArm) + "plant: {timestep: 0.0005}\n");
  const int e = plant->entityHandle("panda");
  Eigen::VectorXd q(plant->entityNq(e)), v(plant->entityNv(e)), q0(q.size()), v0(v.size());
  plant->entityState(e, q, v);
  reference->entityState(reference->entityHandle("panda"), q0, v0);
  CHECK(plant->time() == 0.0);
  CHECK((q - q0).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(v.cwiseAbs().maxCoeff() < 1e-4);
  // Held by the settling servo until a drive commands the joint: it stays there.
  for (int i = 0; i < 500; ++i) plant->step(0.001);
  plant->entityState(e, q, v);
  CHECK((q - q0).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(plant->warnings() == 0);
}

TEST_CASE("MuJoCo plant: settling leaves unactuated joints free (a door swings under its spring)", "[sim]") {
  const char* door = R"(
entities:
  - name: door
    model: door
    actuation: none
    q: {door: 0.2}
    springs: {door: {stiffness: 5.0, damping: 5.0}}
plant: {timestep: 0.0005, settle: 3.0, drives: {integral_time: 0.05}}
)";
  auto plant = makePlant(door);
  // The spring pulls the door back toward 0 during the settling: it is not held at 0.2.
  CHECK(std::abs(plant->jointPosition(plant->jointHandle("door", "door"))) < 0.2 * 0.5);
}

TEST_CASE("MuJoCo plant: a floating robot settles standing on its soles", "[sim]") {
  // JVRC-1 as in the shipped scenes, its soles the scene's contact surfaces (the bottom face of
  // each box at z = −0.1 in the ankle frame): after settling the base stands where the scene
  // put it, to the millimetre the soft contacts sink, and at rest.
  const char* scene = R"(
entities:
  - name: jvrc
    model: jvrc1
    pose: {xyz: [0, 0, 0.8186]}
    q: {R_HIP_P: -0.38, R_KNEE: 0.72, R_ANKLE_P: -0.34, L_HIP_P: -0.38, L_KNEE: 0.72, L_ANKLE_P: -0.34,
        R_SHOULDER_P: -0.3, L_SHOULDER_P: -0.3, R_ELBOW_P: -1.2, L_ELBOW_P: -1.2}
plant:
  timestep: 0.0005
  settle: 0.5
  drives: {integral_time: 0.1}
  geoms:
    - {entity: jvrc, link: R_ANKLE_P_S, type: box, size: [0.21, 0.11, 0.03], pose: {xyz: [0.025, 0, -0.085]},
       replace: true}
    - {entity: jvrc, link: L_ANKLE_P_S, type: box, size: [0.21, 0.11, 0.03], pose: {xyz: [0.025, 0, -0.085]},
       replace: true}
)";
  auto plant = makePlant(scene);
  const int e = plant->entityHandle("jvrc");
  Eigen::VectorXd q(plant->entityNq(e)), v(plant->entityNv(e));
  plant->entityState(e, q, v);
  INFO("base " << q.head<3>().transpose());
  CHECK(std::abs(q(0)) < 2e-3);
  CHECK(std::abs(q(1)) < 2e-3);
  CHECK(std::abs(q(2) - 0.8186) < 3e-3);
  CHECK(v.cwiseAbs().maxCoeff() < 2e-2);
  // The sole is the plant section's box only: one geom on each ankle link.
  const mjModel* m = plant->model();
  const int ankle = plant->frameHandle("jvrc", "R_ANKLE_P_S");
  int geoms = 0;
  for (int g = 0; g < m->ngeom; ++g) geoms += m->geom_bodyid[g] == ankle ? 1 : 0;
  CHECK(geoms == 1);
}

TEST_CASE("MuJoCo plant: interpolated setpoints ramp over their period", "[sim]") {
  // A joint with no load but its own inertia: a stiff servo follows its reference closely. A
  // setpoint 0.01 rad ahead with the velocity 0.01 / 0.004: with interpolation the reference
  // is halfway after 2 ms (the joint with it, to the servo's lag); without, the servo heads for
  // the new position at once and is further.
  const char* arm = R"(
entities:
  - name: panda
    model: panda
    q: {panda_joint4: -1.5}
settings: {gravity: [0, 0, 0]}
)";
  auto run = [&](bool interpolate) {
    auto plant = makePlant(std::string(arm) + "plant: {timestep: 0.0005, drives: {interpolate: " +
                           (interpolate ? "true" : "false") + "}}\n");
    const int j = plant->jointHandle("panda", "panda_joint1");
    mrqp::loop::ServoCommand c;
    c.enabled = true;
    c.kp = 2.0e5;
    c.kd = 2.0e3;
    c.position = 0.0;
    plant->setServo(j, c);
    // What the controller is told of these drives on a simulated bus (docs/loop.md, step 2).
    CHECK(plant->drivesInterpolate() == interpolate);
    plant->step(0.004);
    c.position = 0.01;
    c.velocity = 0.01 / 0.004;
    plant->setServo(j, c);
    plant->step(0.002);
    return plant->jointPosition(j);
  };
  const double ramped = run(true), stepped = run(false);
  INFO("interpolated " << ramped << ", stepped " << stepped);
  CHECK(ramped == Approx(0.005).margin(1e-3));
  CHECK(stepped - ramped > 1e-3);
}

TEST_CASE("Plant section: drives, settle and grasp softness values and errors", "[sim]") {
  const std::string base = "entities: [{name: b, model: rigid_object, mass: 1, inertia: [1, 1, 1]}]\n";
  const mrqp::sim::PlantSpec s = mrqp::sim::loadPlantSpecString(
      base +
          "plant:\n  drives: {integral_time: 0.05, interpolate: true, hold_kp: 100, hold_kd: 3}\n"
          "  settle: 0.25\n  grasp_softness: {timeconst: 0.04, dampratio: 0.7}\n",
      "s.yaml");
  CHECK(s.drives.integral_time == 0.05);
  CHECK(s.drives.interpolate);
  CHECK(s.drives.hold_kp == 100.0);
  CHECK(s.drives.hold_kd == 3.0);
  CHECK(s.settle == 0.25);
  CHECK(s.grasp_timeconst == 0.04);
  CHECK(s.grasp_dampratio == 0.7);
  const mrqp::sim::PlantSpec d = mrqp::sim::loadPlantSpecString(base + "plant: {}\n", "s.yaml");
  CHECK(d.drives.integral_time == 0.0);
  CHECK_FALSE(d.drives.interpolate);
  CHECK(d.settle == 0.0);
  const auto error = [&](const std::string& plant) {
    try {
      (void)mrqp::sim::loadPlantSpecString(base + plant, "s.yaml");
    } catch (const mrqp::scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("plant:\n  drives: {integral_time: 0.0001}\n") ==
        "s.yaml:3: plant.drives.integral_time: must be 0 (none) or at least two time steps (0.001 s)");
  CHECK(error("plant:\n  drives: {ki: 1}\n").find("s.yaml:3: plant.drives.ki: unknown key") == 0);
  CHECK(error("plant:\n  settle: 11\n") == "s.yaml:3: plant.settle: expected at most 10 s, got 11");
  CHECK(error("plant:\n  settle: -1\n").find("s.yaml:3: plant.settle:") == 0);
  CHECK(error("plant:\n  grasp_softness: {timeconst: 0.0001}\n") ==
        "s.yaml:3: plant.grasp_softness.timeconst: must be at least two time steps (0.001 s)");
  CHECK(error("plant:\n  geoms: [{entity: b, type: box, size: [1, 1, 1], replace: maybe}]\n")
            .find("s.yaml:3: plant.geoms[0].replace:") == 0);
}
