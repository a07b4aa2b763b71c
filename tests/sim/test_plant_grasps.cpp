// The plant section's grasps (docs/mujoco.md, "Grasps"): a weld about a given point keeps the held
// body's pose, a `hold: point` grasp (MuJoCo's connect) keeps only the point and lets the body
// swing about it as a compound pendulum (its period against the closed form), and the reader's
// values, defaults and errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim_scenes.hpp"

namespace {

/// Holds every joint of the Panda where it is, with stiff servos.
void holdPanda(mrqp::sim::MujocoPlant& plant) {
  const int e = plant.entityHandle("panda");
  Eigen::VectorXd q(plant.entityNq(e)), v(plant.entityNv(e));
  plant.entityState(e, q, v);
  const std::unique_ptr<mrqp::problem::Entity> model = mrqp::sim::testing::registry().make("panda", "panda");
  for (int k = 0; k < model->nv(); ++k) {
    mrqp::loop::ServoCommand c;
    c.enabled = true;
    c.position = q(k);
    c.kp = 3000.0;
    c.kd = 150.0;
    plant.setServo(plant.jointHandle("panda", model->jointName(k)), c);
  }
}

constexpr double kMass = 2.0;
constexpr double kInertia = 0.004;  // about the centre of mass, each axis
constexpr double kArm = 0.05;       // from the held point to the centre of mass
constexpr double kTilt = 0.2;       // rad, the initial swing angle about world x

/// A 2 kg load hanging from the hand of a held Panda, held at the point 5 cm above its centre of
/// mass (load frame), tilted by kTilt about world x: `grasp` is the plant section's item.
std::unique_ptr<mrqp::sim::MujocoPlant> hangingLoad(const std::string& grasp) {
  const std::string yaml = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0.5], rpy: [0, 0, 0]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0, panda_joint7: 0.785,
        panda_finger_joint1: 0.02}
  - name: load
    model: rigid_object
    mass: 2.0
    inertia: [0.004, 0.004, 0.004]
    pose: {xyz: [0, 0, 0]}
contacts:
  - name: hold
    entity: load
    frame: load
    other: {entity: panda, frame: panda_hand}
    points: [[0, 0, 0.05]]
plant:
  timestep: 0.0005
  geoms: [{entity: load, type: box, size: [0.03, 0.03, 0.03]}]
  pairs: [{between: [panda, load], collide: false}]
  grasps: [)" + grasp + "]\n";
  mrqp::scene::SceneSpec s = mrqp::scene::loadSceneString(yaml, "test.yaml");
  {
    auto probe = mrqp::sim::testing::makePlant(yaml);
    const Eigen::Vector3d pivot =
        probe->framePose(probe->frameHandle("panda", "panda_hand")) * Eigen::Vector3d(0, 0, 0.15);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(kTilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
    s.entities[1].pose.xyz = pivot - r * Eigen::Vector3d(0, 0, kArm);
    s.entities[1].pose.rpy = Eigen::Vector3d(kTilt, 0, 0);
  }
  auto plant = std::make_unique<mrqp::sim::MujocoPlant>(
      s, mrqp::sim::loadPlantSpecString(yaml, "test.yaml"), &mrqp::sim::testing::registry());
  holdPanda(*plant);
  return plant;
}

struct Swing {
  std::vector<double> angle;        ///< of the load about world x, each ms
  double pivot_drift_max = 0.0;     ///< m, the held point of the load from its place on the hand
  double crossing_period = 0.0;     ///< s, twice the mean time between zero crossings
};

Swing swing(mrqp::sim::MujocoPlant& plant, double duration) {
  const int load = plant.frameHandle("load", "load");
  const int hand = plant.frameHandle("panda", "panda_hand");
  const Eigen::Vector3d pivot_in_hand =
      plant.framePose(hand).inverse() * (plant.framePose(load) * Eigen::Vector3d(0, 0, kArm));
  Swing out;
  std::vector<double> crossings;
  const int steps = static_cast<int>(std::lround(duration / 0.001));
  for (int i = 0; i < steps; ++i) {
    plant.step(0.001);
    const Eigen::Isometry3d x = plant.framePose(load);
    const Eigen::Vector3d up = x.linear() * Eigen::Vector3d::UnitZ();  // from the CoM to the point
    out.angle.push_back(std::atan2(-up.y(), up.z()));
    const Eigen::Vector3d pivot = x * Eigen::Vector3d(0, 0, kArm);
    out.pivot_drift_max =
        std::max(out.pivot_drift_max, (plant.framePose(hand).inverse() * pivot - pivot_in_hand).norm());
    const std::size_t n = out.angle.size();
    if (n >= 2 && (out.angle[n - 2] < 0.0) != (out.angle[n - 1] < 0.0)) {
      // linear interpolation of the crossing time
      const double a0 = out.angle[n - 2], a1 = out.angle[n - 1];
      crossings.push_back(0.001 * (static_cast<double>(n) - 1.0 + a0 / (a0 - a1)));
    }
  }
  if (crossings.size() >= 2) {
    out.crossing_period =
        2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
  return out;
}

}  // namespace

TEST_CASE("MuJoCo plant: a grasp held at a point lets the load swing as a compound pendulum", "[sim]") {
  auto plant = hangingLoad("{contact: hold, hold: point, point: [0, 0, 0.05]}");
  const Swing s = swing(*plant, 3.0);
  // The closed form of a compound pendulum: T = 2π √(I_pivot / (m g d)), I_pivot = I + m d²,
  // with the finite-amplitude factor 1 + θ₀²/16.
  const double period = 2.0 * M_PI * std::sqrt((kInertia + kMass * kArm * kArm) / (kMass * 9.81 * kArm)) *
                        (1.0 + kTilt * kTilt / 16.0);
  const double amplitude = -*std::min_element(s.angle.begin(), s.angle.end());  // on the other side
  INFO("period " << s.crossing_period << " s, closed form " << period << " s; amplitude " << amplitude
                 << "; the held point moved " << s.pivot_drift_max << " m on the hand");
  CHECK(s.crossing_period == Approx(period).epsilon(0.03));
  CHECK(amplitude > 0.8 * kTilt);  // it swings through (a weld would hold it at +kTilt)
  CHECK(s.pivot_drift_max < 2e-3);  // the point stays on the hand
  CHECK(plant->warnings() == 0);
}

TEST_CASE("MuJoCo plant: a weld about a point holds the load's pose", "[sim]") {
  auto plant = hangingLoad("{contact: hold, point: [0, 0, 0.05]}");
  const Swing s = swing(*plant, 1.0);
  const auto [lo, hi] = std::minmax_element(s.angle.begin(), s.angle.end());
  INFO("angle " << *lo << " … " << *hi << "; the held point moved " << s.pivot_drift_max << " m");
  CHECK(*lo > kTilt - 0.01);  // it stays tilted: the weld holds the rotation
  CHECK(*hi < kTilt + 0.01);
  CHECK(s.pivot_drift_max < 2e-3);
  CHECK(plant->warnings() == 0);
}

TEST_CASE("Plant section: grasps, their values, defaults and errors", "[sim]") {
  const std::string base = "entities: [{name: b, model: rigid_object, mass: 1, inertia: [1, 1, 1]}]\n";
  const mrqp::sim::PlantSpec s = mrqp::sim::loadPlantSpecString(
      base +
          "plant:\n  grasp_softness: {timeconst: 0.04, dampratio: 0.7}\n"
          "  grasps: [a, {contact: b, hold: point, point: [0, -0.04, 0.055], timeconst: 0.01},\n"
          "           {contact: c, point: [1, 2, 3], dampratio: 2}]\n",
      "s.yaml");
  REQUIRE(s.grasps.size() == 3);
  using Hold = mrqp::sim::GraspSpec::Hold;
  CHECK(s.grasps[0].contact == "a");
  CHECK(s.grasps[0].hold == Hold::Pose);
  CHECK_FALSE(s.grasps[0].point_given);
  CHECK(s.grasps[0].timeconst == 0.04);  // the section's softness
  CHECK(s.grasps[0].dampratio == 0.7);
  CHECK(s.grasps[1].hold == Hold::Point);
  CHECK(s.grasps[1].point.isApprox(Eigen::Vector3d(0, -0.04, 0.055)));
  CHECK(s.grasps[1].timeconst == 0.01);
  CHECK(s.grasps[1].dampratio == 0.7);
  CHECK(s.grasps[2].hold == Hold::Pose);
  CHECK(s.grasps[2].point_given);
  CHECK(s.grasps[2].timeconst == 0.04);
  CHECK(s.grasps[2].dampratio == 2.0);
  CHECK(s.grasps[2].source.line == 5);
  const auto error = [&](const std::string& plant) {
    try {
      (void)mrqp::sim::loadPlantSpecString(base + plant, "s.yaml");
    } catch (const mrqp::scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("plant:\n  grasps: [{contact: a, hold: pinch, point: [0, 0, 0]}]\n") ==
        "s.yaml:3: plant.grasps[0].hold: expected pose or point, got \"pinch\"");
  CHECK(error("plant:\n  grasps: [{contact: a, hold: point}]\n") ==
        "s.yaml:3: plant.grasps[0]: missing required field 'point' (hold: point holds the bodies at that point)");
  CHECK(error("plant:\n  grasps: [{contact: a, timeconst: 0.0001}]\n") ==
        "s.yaml:3: plant.grasps[0].timeconst: must be at least two time steps (0.001 s)");
  CHECK(error("plant:\n  grasps: [{contact: a, torque: 1}]\n").find("s.yaml:3: plant.grasps[0].torque: unknown key") ==
        0);
  CHECK(error("plant:\n  grasps: [{hold: pose}]\n").find("s.yaml:3: plant.grasps[0]: missing required field 'contact'") ==
        0);
}
