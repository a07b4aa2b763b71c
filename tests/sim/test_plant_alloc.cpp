// The MuJoCo plant's cycle allocates nothing: step() (MuJoCo steps with contacts and a weld) and
// every query, counted by the counting allocator (tests/support), which sees MuJoCo's own
// mju_malloc too.
#include <catch2/catch.hpp>

#include "counting_allocator.hpp"
#include "sim_scenes.hpp"

TEST_CASE("MuJoCo plant: stepping and queries do not allocate", "[sim][realtime]") {
  const char* yaml = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0.3]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0}
  - name: box
    model: rigid_object
    mass: 1.0
    inertia: [0.01, 0.01, 0.01]
    pose: {xyz: [0.5, 0.3, 0.2]}
  - name: cube
    model: rigid_object
    mass: 0.5
    inertia: [0.002, 0.002, 0.002]
    pose: {xyz: [0.6, -0.3, 0.5]}
contacts:
  - name: hold
    entity: cube
    frame: cube
    other: {entity: panda, frame: panda_hand}
    points: [[0, 0, 0]]
plant:
  timestep: 0.0005
  pairs: [{between: [box, ground], friction: 1.0}]
  geoms: [{entity: box, type: box, size: [0.1, 0.1, 0.1]}]
  grasps: [hold]
)";
  auto plant = mrqp::sim::testing::makePlant(yaml);
  const int e = plant->entityHandle("panda");
  const int j = plant->jointHandle("panda", "panda_joint2");
  const int f = plant->frameHandle("panda", "panda_hand");
  const int b = plant->entityHandle("box");
  Eigen::VectorXd q(plant->entityNq(e)), v(plant->entityNv(e)), qb(7), vb(6);
  mrqp::loop::ServoCommand c;
  c.enabled = true;
  c.kp = 100.0;
  c.kd = 10.0;
  for (int i = 0; i < 50; ++i) plant->step(0.001);  // the box lands: contacts exist
  double sink = 0.0;
  const long n = mrqp::testing::allocationsIn([&] {
    for (int i = 0; i < 1000; ++i) {
      c.position = -0.3 + 1e-4 * i;
      plant->setServo(j, c);
      plant->step(0.001);
      sink += plant->jointPosition(j) + plant->jointVelocity(j) + plant->jointTorque(j);
      sink += plant->sensorWrench(f).sum() + plant->imu(f).specific_force.sum();
      plant->entityState(e, q, v);
      plant->entityState(b, qb, vb);
      sink += q.sum() + vb.sum() + plant->time();
    }
  });
  CHECK(n == 0);
  CHECK(plant->data()->ncon > 0);
  CHECK(std::isfinite(sink));
}
