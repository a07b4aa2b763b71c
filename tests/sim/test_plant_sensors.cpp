// The MuJoCo plant's sensors: a wrist force/torque sensor of a fixed arm holding a load (sign,
// frame and moment against the statics of the distal bodies), a box with an off-centre CoM welded
// to one or two hands (the sensed wrenches against its weight at its CoM, closed form), an IMU at
// rest and in free fall, and the plant section's reader and its errors.
#include <catch2/catch.hpp>

#include <cmath>

#include "scene/scene_yaml.hpp"
#include "sim/sensor_noise.hpp"
#include "sim_scenes.hpp"

using mrqp::sim::testing::makePlant;

namespace {

/// Holds every joint of `entity` where it is, with stiff servos.
void holdAll(mrqp::sim::MujocoPlant& plant, const std::string& entity) {
  const int e = plant.entityHandle(entity);
  Eigen::VectorXd q(plant.entityNq(e)), v(plant.entityNv(e));
  plant.entityState(e, q, v);
  const std::unique_ptr<mrqp::problem::Entity> model = mrqp::sim::testing::registry().make("panda", entity);
  for (int k = 0; k < model->nv(); ++k) {
    mrqp::loop::ServoCommand c;
    c.enabled = true;
    c.position = q(k);
    c.kp = 3000.0;
    c.kd = 150.0;
    plant.setServo(plant.jointHandle(entity, model->jointName(k)), c);
  }
}

/// The wrench, in `frame`'s axes, that the weight of the bodies of the subtree at `body` (and
/// `extra_mass` at `extra_com`) exerts about the frame origin: the statics of the distal side.
mrqp::loop::Vector6d distalWeight(const mjModel* m, const mjData* d, int body, double extra_mass,
                                  const Eigen::Vector3d& extra_com, int at = -1) {
  double mass = extra_mass;
  Eigen::Vector3d moment_sum = extra_mass * extra_com;
  for (int b = 1; b < m->nbody; ++b) {
    int a = b;
    while (a > 0 && a != body) a = m->body_parentid[a];
    if (a != body) continue;
    mass += m->body_mass[b];
    moment_sum +=
        m->body_mass[b] * Eigen::Vector3d(d->xipos[3 * b], d->xipos[3 * b + 1], d->xipos[3 * b + 2]);
  }
  const Eigen::Vector3d com = moment_sum / mass;
  const Eigen::Vector3d f(0, 0, -9.81 * mass);
  const int a = at >= 0 ? at : body;  // the frame: origin and axes
  const Eigen::Vector3d o(d->xpos[3 * a], d->xpos[3 * a + 1], d->xpos[3 * a + 2]);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = d->xmat[9 * a + 3 * r + c];
  mrqp::loop::Vector6d w;
  w.head<3>() = R.transpose() * f;
  w.tail<3>() = R.transpose() * (com - o).cross(f);
  return w;
}

const char* kArm = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0.5], rpy: [0, 0, 0.4]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0, panda_joint7: 0.785,
        panda_finger_joint1: 0.02}
)";

}  // namespace

TEST_CASE("MuJoCo plant: a wrist sensor of a held arm reads the weight of the hand", "[sim]") {
  auto plant = makePlant(std::string(kArm) + "plant: {timestep: 0.0005}\n");
  holdAll(*plant, "panda");
  for (int i = 0; i < 1500; ++i) plant->step(0.001);
  const int frame = plant->frameHandle("panda", "panda_hand");
  REQUIRE(frame >= 0);
  const mrqp::loop::Vector6d w = plant->sensorWrench(frame);
  const mrqp::loop::Vector6d expected =
      distalWeight(plant->model(), plant->data(), frame, 0.0, Eigen::Vector3d::Zero());
  INFO("measured " << w.transpose() << "\nexpected " << expected.transpose());
  CHECK((w.head<3>() - expected.head<3>()).norm() < 1e-3 * expected.head<3>().norm() + 1e-6);
  CHECK((w.tail<3>() - expected.tail<3>()).norm() < 1e-4);
  // Sign: the hand pulls its proximal side down, in world axes.
  const Eigen::Vector3d f_world = plant->framePose(frame).linear() * w.head<3>();
  CHECK(f_world.z() < 0.0);
}

TEST_CASE("MuJoCo plant: a sensor at a marker frame measures across its carrying ancestor", "[sim]") {
  // panda_hand_tcp is a massless link without geometry fixed to the hand: a sensor there reads
  // the hand's (and fingers') weight, about the tcp origin in the tcp's axes.
  auto plant = makePlant(std::string(kArm) + "plant: {timestep: 0.0005}\n");
  holdAll(*plant, "panda");
  for (int i = 0; i < 1500; ++i) plant->step(0.001);
  const int tcp = plant->frameHandle("panda", "panda_hand_tcp");
  const int hand = plant->frameHandle("panda", "panda_hand");
  REQUIRE(tcp >= 0);
  const mrqp::loop::Vector6d w = plant->sensorWrench(tcp);
  const mrqp::loop::Vector6d expected =
      distalWeight(plant->model(), plant->data(), hand, 0.0, Eigen::Vector3d::Zero(), tcp);
  INFO("measured " << w.transpose() << "\nexpected " << expected.transpose());
  CHECK(expected.head<3>().norm() > 5.0);
  CHECK((w.head<3>() - expected.head<3>()).norm() < 1e-3 * expected.head<3>().norm());
  CHECK((w.tail<3>() - expected.tail<3>()).norm() < 1e-4);
}

TEST_CASE("MuJoCo plant: a grasped load adds its weight at the wrist (weld forces)", "[sim]") {
  // A 2 kg box held 0.12 m beyond the hand frame: a grasp of the plant section (a weld).
  const std::string yaml = std::string(kArm) + R"(
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
    points: [[0, 0, 0]]
plant:
  timestep: 0.0005
  geoms: [{entity: load, type: box, size: [0.03, 0.03, 0.03]}]
  grasps: [hold]
)";
  // Place the load 0.12 m along the hand's z: first find the hand's pose.
  mrqp::scene::SceneSpec s = mrqp::scene::loadSceneString(yaml, "test.yaml");
  {
    auto probe = makePlant(yaml);
    const Eigen::Isometry3d hand = probe->framePose(probe->frameHandle("panda", "panda_hand"));
    const Eigen::Vector3d p = hand * Eigen::Vector3d(0, 0, 0.12);
    s.entities[1].pose.xyz = p;
    s.entities[1].pose.rpy = hand.linear().eulerAngles(2, 1, 0).reverse();
  }
  const mrqp::sim::PlantSpec ps = mrqp::sim::loadPlantSpecString(yaml, "test.yaml");
  mrqp::sim::MujocoPlant plant(s, ps, &mrqp::sim::testing::registry());
  holdAll(plant, "panda");
  const int load = plant.frameHandle("load", "load");
  const Eigen::Vector3d start = plant.framePose(load).translation();
  for (int i = 0; i < 2000; ++i) plant.step(0.001);
  const int frame = plant.frameHandle("panda", "panda_hand");
  const Eigen::Isometry3d hand = plant.framePose(frame);
  const Eigen::Vector3d load_at = plant.framePose(load).translation();
  // The weld holds the load where it was relative to the hand.
  CHECK((hand.inverse() * load_at - Eigen::Vector3d(0, 0, 0.12)).norm() < 2e-3);
  CHECK((load_at - start).norm() < 0.05);
  const mrqp::loop::Vector6d w = plant.sensorWrench(frame);
  const mrqp::loop::Vector6d expected = distalWeight(plant.model(), plant.data(), frame, 2.0, load_at);
  INFO("measured " << w.transpose() << "\nexpected " << expected.transpose());
  CHECK((w.head<3>() - expected.head<3>()).norm() < 2e-3 * expected.head<3>().norm());
  CHECK((w.tail<3>() - expected.tail<3>()).norm() < 2e-3 * expected.tail<3>().norm() + 1e-3);
}

TEST_CASE("MuJoCo plant: an IMU at rest reads −g in its axes and no rate", "[sim]") {
  const char* yaml = R"(
entities:
  - name: door
    model: door
    pose: {xyz: [1, 0, 0], rpy: [0.3, -0.5, 0.8]}
    actuation: none
plant: {timestep: 0.001}
)";
  auto plant = makePlant(yaml);
  const int base = plant->frameHandle("door", "base_link");
  REQUIRE(base >= 0);
  plant->step(0.001);
  const mrqp::loop::ImuSample s = plant->imu(base);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  CHECK((s.specific_force - R.transpose() * Eigen::Vector3d(0, 0, 9.81)).norm() < 1e-9);
  CHECK(s.angular_velocity.norm() < 1e-12);
  CHECK(s.orientation.angularDistance(Eigen::Quaterniond(R)) < 1e-9);
}

TEST_CASE("Plant section: values, defaults and errors", "[sim]") {
  const std::string head = "entities: [{name: box, model: rigid_object}]\n";
  SECTION("absent: the ideal plant") {
    const mrqp::sim::PlantSpec p = mrqp::sim::loadPlantSpecString(head, "a.yaml");
    CHECK_FALSE(p.present);
    CHECK(p.simulator == "ideal");
  }
  SECTION("values") {
    const mrqp::sim::PlantSpec p = mrqp::sim::loadPlantSpecString(head + R"(
plant:
  timestep: 0.001
  seed: 42
  contact: {friction: 0.6, timeconst: 0.01}
  pairs: [{between: [box, ground], friction: 1.2}]
  noise: {force: {stddev: 0.5, bias: 0.1}, gyro: {stddev: 0.001}}
)",
                                                                  "a.yaml");
    CHECK(p.simulator == "mujoco");
    CHECK(p.timestep == 0.001);
    CHECK(p.seed == 42);
    CHECK(p.contact.friction == 0.6);
    CHECK(p.contact.timeconst == 0.01);
    REQUIRE(p.pairs.size() == 1);
    CHECK(p.pairs[0].params.friction == 1.2);
    CHECK(p.pairs[0].params.timeconst == 0.01);  // the section's default
    CHECK(p.pairs[0].collide);
    CHECK(p.noise.force.stddev == 0.5);
    CHECK(p.noise.force.bias == 0.1);
    CHECK(p.noise.gyro.stddev == 0.001);
  }
  const auto error = [&](const std::string& plant) {
    try {
      mrqp::sim::loadPlantSpecString(head + plant, "a.yaml");
    } catch (const mrqp::scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("plant: {timestep: -1}\n") == "a.yaml:2: plant.timestep: expected a number > 0, got -1");
  CHECK(error("plant:\n  contact: {friction: 0.5, stiff: 3}\n") ==
        "a.yaml:3: plant.contact.stiff: unknown key");
  CHECK(error("plant: {simulator: bullet}\n") ==
        "a.yaml:2: plant.simulator: expected mujoco or ideal, got \"bullet\"");
  CHECK(error("plant:\n  geoms:\n    - {entity: box, type: cone, size: [1]}\n") ==
        "a.yaml:4: plant.geoms[0].type: expected box, sphere, cylinder or capsule, got \"cone\"");
  CHECK(error("plant:\n  contact: {timeconst: 0.0001}\n") ==
        "a.yaml:3: plant.contact.timeconst: must be at least two time steps (0.001 s), or the "
        "contact is stiffer than the integrator can resolve");
}

TEST_CASE("Sensor noise: bias and the spread of the noise", "[sim]") {
  mrqp::sim::SensorNoiseSpec spec;
  spec.force = {0.5, 0.2};
  mrqp::sim::SensorNoise noise(spec, 3);
  double sum = 0.0, sq = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = noise.wrench(mrqp::loop::Vector6d::Zero())(0);
    sum += x;
    sq += x * x;
  }
  const double mean = sum / n, sd = std::sqrt(sq / n - mean * mean);
  CHECK(mean == Approx(0.2).margin(4 * 0.5 / std::sqrt(n)));
  CHECK(sd == Approx(0.5).epsilon(0.03));
  CHECK(noise.jointPosition(1.25) == 1.25);  // no noise configured
}

TEST_CASE("Plant section: names are checked against the scene", "[sim]") {
  const std::string head =
      "entities:\n  - {name: box, model: rigid_object, mass: 1.0, inertia: [0.01, 0.01, 0.01]}\n";
  const auto error = [&](const std::string& plant) {
    try {
      makePlant(head + plant);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("plant:\n  pairs: [{between: [box, boxx]}]\n") ==
        "test.yaml:4: plant.pairs[0].between: unknown entity 'boxx'");
  CHECK(error("plant:\n  geoms:\n    - {entity: box, link: lid, type: sphere, size: [0.1]}\n") ==
        "test.yaml:5: plant.geoms[0].link: entity 'box' has no link 'lid'");
  CHECK(error("plant:\n  grasps: [nothing]\n") ==
        "test.yaml:4: plant.grasps[0]: 'nothing' is not a contact between two entities of the scene");
}

namespace {

/// The weight of the bodies of the subtree at `body` as a world wrench (moment about `p`; force).
mrqp::loop::Vector6d subtreeWeightAbout(const mjModel* m, const mjData* d, int body, const Eigen::Vector3d& p) {
  mrqp::loop::Vector6d w = mrqp::loop::Vector6d::Zero();
  for (int b = 1; b < m->nbody; ++b) {
    int a = b;
    while (a > 0 && a != body) a = m->body_parentid[a];
    if (a != body) continue;
    const Eigen::Vector3d f(0, 0, -9.81 * m->body_mass[b]);
    const Eigen::Vector3d x(d->xipos[3 * b], d->xipos[3 * b + 1], d->xipos[3 * b + 2]);
    w.head<3>() += (x - p).cross(f);
    w.tail<3>() += f;
  }
  return w;
}

/// A sensor's reading (frame axes, moment about the frame origin) as a world wrench (moment about
/// `p`; force).
mrqp::loop::Vector6d worldWrenchAbout(const mrqp::sim::MujocoPlant& plant, int frame, const Eigen::Vector3d& p) {
  const mrqp::loop::Vector6d w = plant.sensorWrench(frame);
  const Eigen::Isometry3d x = plant.framePose(frame);
  const Eigen::Vector3d f = x.linear() * w.head<3>();
  mrqp::loop::Vector6d out;
  out.head<3>() = x.linear() * w.tail<3>() + (x.translation() - p).cross(f);
  out.tail<3>() = f;
  return out;
}

// The statics of a box welded to one or two Panda hands. The box: 0.941 kg, its CoM at
// (0.04, 0.06, −0.02) m in its own frame (box_mass's box), placed between the hands at `box_xyz`
// relative to their mid-point with orientation `box_rpy`. Each grasp is a weld about the box's
// origin, so the box's moment m g × c about that origin reaches the hands as weld torques.
const double kBoxMass = 0.941;
const Eigen::Vector3d kBoxCom(0.04, 0.06, -0.02);

std::string weldedBoxYaml(bool two_hands) {
  std::string y = R"(
entities:
  - name: panda_a
    model: panda
    pose: {xyz: [0, -0.3, 0.5], rpy: [0, 0, 0.3]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0, panda_joint7: 0.785,
        panda_finger_joint1: 0.02}
)";
  if (two_hands) {
    y += R"(
  - name: panda_b
    model: panda
    pose: {xyz: [0, 0.3, 0.5], rpy: [0, 0, -0.3]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0, panda_joint7: 0.785,
        panda_finger_joint1: 0.02}
)";
  }
  y += R"(
  - name: box
    model: rigid_object
    mass: 0.941
    com: [0.04, 0.06, -0.02]
    inertia: [0.0212, 0.0102, 0.0251]
    pose: {xyz: [0, 0, 0]}
contacts:
  - {name: hold_a, entity: box, frame: box, other: {entity: panda_a, frame: panda_hand}, points: [[0, 0, 0]]}
)";
  if (two_hands) {
    y += "  - {name: hold_b, entity: box, frame: box, other: {entity: panda_b, frame: panda_hand}, "
         "points: [[0, 0, 0]]}\n";
  }
  y += R"(
plant:
  timestep: 0.0005
  geoms: [{entity: box, type: box, size: [0.1, 0.1, 0.1]}]
)";
  y += two_hands ? "  pairs: [{between: [panda_a, box], collide: false}, {between: [panda_b, box], collide: false},\n"
                   "          {between: [panda_a, panda_b], collide: false}]\n  grasps: [hold_a, hold_b]\n"
                 : "  pairs: [{between: [panda_a, box], collide: false}]\n  grasps: [hold_a]\n";
  return y;
}

struct WeldedBox {
  std::unique_ptr<mrqp::sim::MujocoPlant> plant;
  std::vector<int> hands;  // sensor frames
  int box = -1;
};

/// Builds the scene with the box at `offset` from the hands' mid-point (world axes) and
/// orientation `rpy`, holds the arms with stiff servos and lets it settle for 2 s.
WeldedBox settleWeldedBox(bool two_hands, const Eigen::Vector3d& offset, const Eigen::Vector3d& rpy) {
  const std::string yaml = weldedBoxYaml(two_hands);
  mrqp::scene::SceneSpec s = mrqp::scene::loadSceneString(yaml, "test.yaml");
  {
    const mrqp::sim::PlantSpec none = mrqp::sim::loadPlantSpecString(
        yaml.substr(0, yaml.find("contacts:")) + "plant: {timestep: 0.0005}\n", "probe.yaml");
    mrqp::sim::MujocoPlant probe(mrqp::scene::loadSceneString(yaml.substr(0, yaml.find("contacts:")), "probe.yaml"),
                                 none, &mrqp::sim::testing::registry());
    Eigen::Vector3d mid = probe.framePose(probe.frameHandle("panda_a", "panda_hand")).translation();
    if (two_hands) {
      mid = 0.5 * (mid + probe.framePose(probe.frameHandle("panda_b", "panda_hand")).translation());
    }
    s.entities.back().pose.xyz = mid + offset;
    s.entities.back().pose.rpy = rpy;
  }
  WeldedBox out;
  out.plant = std::make_unique<mrqp::sim::MujocoPlant>(s, mrqp::sim::loadPlantSpecString(yaml, "test.yaml"),
                                                       &mrqp::sim::testing::registry());
  holdAll(*out.plant, "panda_a");
  out.hands.push_back(out.plant->frameHandle("panda_a", "panda_hand"));
  if (two_hands) {
    holdAll(*out.plant, "panda_b");
    out.hands.push_back(out.plant->frameHandle("panda_b", "panda_hand"));
  }
  out.box = out.plant->frameHandle("box", "box");
  for (int i = 0; i < 2000; ++i) out.plant->step(0.001);
  return out;
}

/// The scalar part of MuJoCo's weld error quaternion q2⁻¹ q1 r of the first weld (r: the weld's
/// relative rotation, eq_data[6..9]): ±1 when the weld holds. The sign is the hemisphere in
/// which MuJoCo 2.2 writes the weld's rotational rows (their torque's sign depends on it).
double weldHemisphere(const mjModel* m, const mjData* d) {
  for (int k = 0; k < m->neq; ++k) {
    if (m->eq_type[k] != mjEQ_WELD) continue;
    const mjtNum* a = d->xquat + 4 * m->eq_obj1id[k];
    const mjtNum* b = d->xquat + 4 * m->eq_obj2id[k];
    const mjtNum* r = m->eq_data + mjNEQDATA * k + 6;
    const Eigen::Quaterniond c = Eigen::Quaterniond(b[0], b[1], b[2], b[3]).conjugate() *
                                 Eigen::Quaterniond(a[0], a[1], a[2], a[3]) * Eigen::Quaterniond(r[0], r[1], r[2], r[3]);
    return c.w();
  }
  return 0.0;
}

/// Checks Σ sensed wrenches = the hands' weights + the box's weight m g at its CoM (closed form
/// from the scene's mass and CoM), about the box's origin in world axes.
void checkWeldedBoxStatics(const WeldedBox& w) {
  const mjModel* m = w.plant->model();
  const mjData* d = w.plant->data();
  const Eigen::Isometry3d box = w.plant->framePose(w.box);
  const Eigen::Vector3d o = box.translation();
  const Eigen::Vector3d c = box.linear() * kBoxCom;  // the CoM from the origin, world axes
  // The box is at rest: what the hands carry is weight, not inertia.
  const int e = w.plant->entityHandle("box");
  Eigen::VectorXd q(w.plant->entityNq(e)), v(w.plant->entityNv(e));
  w.plant->entityState(e, q, v);
  REQUIRE(v.norm() < 1e-3);

  mrqp::loop::Vector6d sensed = mrqp::loop::Vector6d::Zero(), expected = mrqp::loop::Vector6d::Zero();
  for (int h : w.hands) {
    sensed += worldWrenchAbout(*w.plant, h, o);
    expected += subtreeWeightAbout(m, d, h, o);  // a frame handle is its MuJoCo body
  }
  const Eigen::Vector3d g(0, 0, -9.81 * kBoxMass);
  expected.head<3>() += c.cross(g);  // m g × c
  expected.tail<3>() += g;
  INFO("sensed   " << sensed.transpose() << "\nexpected " << expected.transpose()
                   << "\nbox's own moment m g x c " << c.cross(g).transpose());
  // At rest the statics are exact up to the solver's residual (measured: 2e-9 N·m, 2e-9 N);
  // MuJoCo 2.2's own cfrc_int is off by 1.3–2.0 N·m here (its weld torques, mujoco_plant.cpp).
  CHECK((sensed.tail<3>() - expected.tail<3>()).norm() < 1e-5);
  CHECK((sensed.head<3>() - expected.head<3>()).norm() < 1e-5);
}

}  // namespace

TEST_CASE("MuJoCo plant: a box welded to two hands: the sensed wrenches sum to its weight at its CoM",
          "[sim]") {
  SECTION("level box") {
    const WeldedBox w = settleWeldedBox(true, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    checkWeldedBoxStatics(w);
    CHECK(std::abs(weldHemisphere(w.plant->model(), w.plant->data())) == Approx(1.0).margin(1e-3));
  }
  SECTION("turned box, off the hands' mid-point") {
    checkWeldedBoxStatics(settleWeldedBox(true, Eigen::Vector3d(0.03, -0.05, 0.02), Eigen::Vector3d(0.3, -0.2, 0.6)));
  }
}

TEST_CASE("MuJoCo plant: a box welded to one hand: the sensor reads its weight at its CoM", "[sim]") {
  SECTION("level box") { checkWeldedBoxStatics(settleWeldedBox(false, Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d::Zero())); }
  SECTION("turned box") {
    checkWeldedBoxStatics(settleWeldedBox(false, Eigen::Vector3d(0.0, 0.08, -0.04), Eigen::Vector3d(-0.4, 0.3, 1.0)));
  }
  SECTION("the same pose given a turn of 2π more: the other hemisphere of the weld's quaternion") {
    // The box's quaternion changes sign (same rotation), so MuJoCo writes the weld's rows with
    // the opposite sign: the reading must not change.
    const Eigen::Vector3d rpy(-0.4, 0.3, 1.0);
    const WeldedBox a = settleWeldedBox(false, Eigen::Vector3d(0.0, 0.08, -0.04), rpy);
    const WeldedBox b = settleWeldedBox(false, Eigen::Vector3d(0.0, 0.08, -0.04), rpy + Eigen::Vector3d(0, 0, 2 * M_PI));
    const double ha = weldHemisphere(a.plant->model(), a.plant->data());
    const double hb = weldHemisphere(b.plant->model(), b.plant->data());
    CHECK(std::abs(ha) == Approx(1.0).margin(1e-3));
    CHECK(ha * hb == Approx(-1.0).margin(1e-3));
    checkWeldedBoxStatics(b);
    CHECK((a.plant->sensorWrench(a.hands[0]) - b.plant->sensorWrench(b.hands[0])).norm() < 1e-6);
  }
}
