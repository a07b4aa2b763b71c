// The MuJoCo plant against independent references: a free fall against its closed form, the
// Panda's mass matrix and bias forces against the generated model of the same URDF (joint order,
// placement and conventions), the floating base's twist against finite differences of its pose,
// and a joint servo's step response against the second-order closed form.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "model/model_traits.hpp"
#include "sim_scenes.hpp"

using mrqp::sim::testing::makePlant;
using mrqp::sim::testing::registry;

namespace {

const char* kFreeFall = R"(
settings: {gravity: [0, 0, -9.81]}
entities:
  - name: box
    model: rigid_object
    mass: 2.0
    inertia: [0.02, 0.03, 0.04]
    pose: {xyz: [0.3, -0.2, 5.0], rpy: [0.2, 0.1, -0.4]}
plant:
  timestep: 0.0005
  geoms: [{entity: box, type: box, size: [0.2, 0.2, 0.2]}]
)";

}  // namespace

TEST_CASE("MuJoCo plant: a free-falling rigid object follows the closed form", "[sim]") {
  auto plant = makePlant(kFreeFall);
  const int box = plant->entityHandle("box");
  REQUIRE(box >= 0);
  REQUIRE(plant->entityNq(box) == 7);
  REQUIRE(plant->entityNv(box) == 6);
  const double dt = 0.001;
  const int cycles = 500;
  for (int i = 0; i < cycles; ++i) {
    plant->step(dt);
  }
  const double t = plant->time();
  CHECK(t == Approx(cycles * dt).margin(1e-9));
  Eigen::VectorXd q(7), v(6);
  plant->entityState(box, q, v);
  // z(t) = z0 − g t²/2; semi-implicit Euler at step h is off by g t h / 2.
  const double g = 9.81, h = plant->timestep();
  CHECK(q(0) == Approx(0.3).margin(1e-12));
  CHECK(q(1) == Approx(-0.2).margin(1e-12));
  CHECK(q(2) == Approx(5.0 - 0.5 * g * t * t).margin(g * t * h));
  // The body-frame linear velocity is Rᵀ (0, 0, −g t); no rotation.
  const Eigen::Quaterniond quat(q(3), q(4), q(5), q(6));
  const Eigen::Vector3d v_body = quat.toRotationMatrix().transpose() * Eigen::Vector3d(0, 0, -g * t);
  CHECK((v.head<3>()).norm() < 1e-12);
  CHECK((v.tail<3>() - v_body).norm() < 1e-9);
  // Free fall: the accelerometer reads no specific force.
  const mrqp::loop::ImuSample s = plant->imu(plant->frameHandle("box", "box"));
  CHECK(s.specific_force.norm() < 1e-9);
}

TEST_CASE("MuJoCo plant: the Panda's M and bias equal the generated model's", "[sim]") {
  const char* yaml = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0.1, -0.2, 0.6274], rpy: [0.3, -0.2, 0.5]}
plant: {timestep: 0.001}
)";
  auto plant = makePlant(yaml);
  const int e = plant->entityHandle("panda");
  std::unique_ptr<mrqp::problem::Entity> model = registry().make("panda", "panda");
  mrqp::problem::Pose base;
  base.R =
      (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  base.p = Eigen::Vector3d(0.1, -0.2, 0.6274);
  model->setBasePose(base);
  const int nv = model->nv();
  REQUIRE(plant->entityNv(e) == nv);
  const mjModel* m = plant->model();
  const int nmj = m->nv;
  // G maps the generated model's velocities to MuJoCo's: identity on the joints they share, the
  // mimic joint (the second finger) follows its master with its multiplier. Then the generated
  // model's M and bias are Gᵀ M_mj G and Gᵀ bias_mj.
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nmj, nv);
  for (int k = 0; k < nv; ++k) {
    const int h = plant->jointHandle("panda", model->jointName(k));
    REQUIRE(h >= 0);
    G(plant->jointDof(h), k) = 1.0;
  }
  const auto& mimics = plant->mjcf().entities.at(0).mimics;
  REQUIRE(mimics.size() == 1);
  REQUIRE(nmj == nv + 1);
  for (const mrqp::sim::MjcfMimic& mm : mimics) {
    const int master = model->jointIndex(mm.master);
    REQUIRE(master >= 0);
    const int jid = mj_name2id(m, mjOBJ_JOINT, ("panda/" + mm.joint).c_str());
    REQUIRE(jid >= 0);
    G(m->jnt_dofadr[jid], master) = mm.multiplier;
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<mjtNum> full(static_cast<std::size_t>(nmj * nmj));
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(nv), v(nv);
    for (int k = 0; k < nv; ++k) {
      const double lo = model->qLower()(k), hi = model->qUpper()(k);
      q(k) = lo + (hi - lo) * u(rng);
      v(k) = 2.0 * u(rng) - 1.0;
    }
    plant->setEntityState(e, q, v);
    model->q() = q;
    model->v() = v;
    model->update();
    mj_fullM(m, full.data(), plant->data()->qM);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Mmj(
        full.data(), nmj, nmj);
    const Eigen::Map<const Eigen::VectorXd> bmj(plant->data()->qfrc_bias, nmj);
    const Eigen::MatrixXd M = G.transpose() * Mmj * G;
    const Eigen::VectorXd bias = G.transpose() * bmj;
    const double m_err = (M - model->massMatrix()).cwiseAbs().maxCoeff();
    const double b_err = (bias - model->bias()).cwiseAbs().maxCoeff();
    const double scale = model->massMatrix().cwiseAbs().maxCoeff();
    INFO("trial " << trial << ": |ΔM| " << m_err << " (max |M| " << scale << "), |Δbias| " << b_err);
    CHECK(m_err < 1e-7);
    CHECK(b_err < 1e-7);
  }
}

TEST_CASE("MuJoCo plant: a floating body's twist matches finite differences of its pose", "[sim]") {
  const char* yaml = R"(
settings: {gravity: [0, 0, 0]}
entities:
  - name: box
    model: rigid_object
    mass: 3.0
    com: [0.05, -0.02, 0.01]
    inertia: [0.05, 0.04, 0.03]
    pose: {xyz: [0, 0, 2.0], rpy: [0.4, -0.3, 1.1]}
plant:
  timestep: 0.0001
  geoms: [{entity: box, type: sphere, size: [0.1]}]
)";
  auto plant = makePlant(yaml);
  const int e = plant->entityHandle("box");
  Eigen::VectorXd q(7), v(6), q1(7), v1(6);
  plant->entityState(e, q, v);
  v << 0.7, -0.4, 0.9, 0.3, -0.5, 0.2;  // (ω; v) in the body frame
  plant->setEntityState(e, q, v);
  plant->entityState(e, q, v1);
  CHECK((v1 - v).norm() < 1e-12);
  const double h = plant->timestep();
  plant->step(h);
  plant->entityState(e, q1, v1);
  const Eigen::Quaterniond r0(q(3), q(4), q(5), q(6)), r1(q1(3), q1(4), q1(5), q1(6));
  const Eigen::Matrix3d R0 = r0.toRotationMatrix();
  // Body-frame velocity of the origin and angular velocity from one step of the pose.
  const Eigen::Vector3d v_fd = R0.transpose() * (q1.head<3>() - q.head<3>()) / h;
  const Eigen::AngleAxisd d(R0.transpose() * r1.toRotationMatrix());
  const Eigen::Vector3d w_fd = d.axis() * d.angle() / h;
  INFO("ω " << v.head<3>().transpose() << " vs " << w_fd.transpose());
  INFO("v " << v.tail<3>().transpose() << " vs " << v_fd.transpose());
  CHECK((w_fd - v.head<3>()).norm() < 1e-3);
  CHECK((v_fd - v.tail<3>()).norm() < 1e-3);
}

TEST_CASE("MuJoCo plant: a servo's step response is the second-order closed form", "[sim]") {
  // The Panda's first joint turns about the vertical: gravity does no work on it. The other
  // joints are held by stiff servos; the first one's inertia about its axis comes from the
  // generated model's mass matrix at that configuration.
  const std::string integrator = GENERATE(as<std::string>{}, "euler", "implicit");
  const std::string yaml = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0, panda_joint7: 0.785}
plant: {timestep: 0.0002, integrator: )" +
                           integrator + "}\n";
  INFO("integrator " << integrator);
  auto plant = makePlant(yaml);
  const int e = plant->entityHandle("panda");
  std::unique_ptr<mrqp::problem::Entity> model = registry().make("panda", "panda");
  Eigen::VectorXd q(model->nq()), v(model->nv());
  plant->entityState(e, q, v);
  model->q() = q;
  model->v().setZero();
  model->update();
  const double inertia = model->massMatrix()(0, 0);
  const double kp = 40.0, zeta = 0.3;
  const double wn = std::sqrt(kp / inertia);
  const double kd = 2.0 * zeta * wn * inertia;
  const double step = 0.2;
  for (int k = 0; k < model->nv(); ++k) {
    mrqp::loop::ServoCommand c;
    c.enabled = true;
    c.position = q(k) + (k == 0 ? step : 0.0);
    c.kp = k == 0 ? kp : 20000.0;
    c.kd = k == 0 ? kd : 400.0;
    plant->setServo(plant->jointHandle("panda", model->jointName(k)), c);
  }
  const int j0 = plant->jointHandle("panda", "panda_joint1");
  const double wd = wn * std::sqrt(1.0 - zeta * zeta);
  double worst = 0.0;
  for (int i = 1; i <= 3000; ++i) {
    plant->step(0.001);
    const double t = plant->time();
    const double expected =
        q(0) + step * (1.0 - std::exp(-zeta * wn * t) *
                                 (std::cos(wd * t) + zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t)));
    worst = std::max(worst, std::abs(plant->jointPosition(j0) - expected));
  }
  INFO("inertia " << inertia << ", ωn " << wn << ", worst error " << worst);
  CHECK(worst < 0.02 * step);
  CHECK(plant->warnings() == 0);
  // The drive's torque: kp (q_ref − q) + kd (0 − v).
  const double tau = kp * (q(0) + step - plant->jointPosition(j0)) - kd * plant->jointVelocity(j0);
  CHECK(plant->jointTorque(j0) == Approx(tau).margin(1e-9));
}

TEST_CASE("MuJoCo plant: two plants of one scene step identically", "[sim]") {
  // The loop's runs over the simulated buses are deterministic only if the plant is.
  const char* yaml = R"(
entities:
  - name: panda
    model: panda
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0}
  - name: box
    model: rigid_object
    mass: 1.0
    inertia: [0.01, 0.01, 0.01]
    pose: {xyz: [0.5, 0.2, 0.3], rpy: [0.3, 0.2, 0.1]}
plant: {geoms: [{entity: box, type: box, size: [0.1, 0.1, 0.1]}]}
)";
  auto a = makePlant(yaml);
  auto b = makePlant(yaml);
  const int j = a->jointHandle("panda", "panda_joint1");
  mrqp::loop::ServoCommand c;
  c.enabled = true;
  c.kp = 300.0;
  c.kd = 20.0;
  for (int i = 0; i < 600; ++i) {
    c.position = 0.5 * std::sin(0.01 * i);
    a->setServo(j, c);
    b->setServo(j, c);
    a->step(0.001);
    b->step(0.001);
  }
  const int nq = a->model()->nq, nv = a->model()->nv;
  CHECK(std::equal(a->data()->qpos, a->data()->qpos + nq, b->data()->qpos));
  CHECK(std::equal(a->data()->qvel, a->data()->qvel + nv, b->data()->qvel));
  CHECK(a->data()->ncon > 0);  // the box has landed: contacts took part
  CHECK(a->warnings() == 0);
}

TEST_CASE("MuJoCo plant: a diverging simulation is counted in warnings()", "[sim]") {
  auto plant = makePlant("entities:\n  - {name: panda, model: panda}\nplant: {timestep: 0.001}\n");
  const int j = plant->jointHandle("panda", "panda_joint7");
  mrqp::loop::ServoCommand c;
  c.enabled = true;
  c.torque = 1e300;  // finite, but no state survives it
  plant->setServo(j, c);
  CHECK(plant->warnings() == 0);
  for (int i = 0; i < 5; ++i) plant->step(0.001);
  CHECK(plant->warnings() > 0);
}

TEST_CASE("MuJoCo plant: a pair that does not collide passes through", "[sim]") {
  const std::string head = R"(
entities:
  - name: box
    model: rigid_object
    mass: 1.0
    inertia: [0.01, 0.01, 0.01]
    pose: {xyz: [0, 0, 0.3]}
)";
  for (const bool collide : {true, false}) {
    auto plant = makePlant(
        head + "plant: {pairs: [{between: [box, ground], collide: " + (collide ? "true" : "false") + "}]}\n");
    for (int i = 0; i < 500; ++i) plant->step(0.001);
    Eigen::VectorXd q(7), v(6);
    plant->entityState(plant->entityHandle("box"), q, v);
    INFO("collide " << collide << ": z " << q(2));
    // The box of the same inertia has sides of sqrt(6 · 0.01 / 1) = 0.245 m: it rests at 0.1225.
    CHECK((collide ? std::abs(q(2) - 0.1225) < 0.005 : q(2) < -0.5));
  }
}
