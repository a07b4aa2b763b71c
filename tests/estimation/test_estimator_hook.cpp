// The estimator on the controller's loop (EstimatorHook) with the door_estimate scene on a plant
// whose wrist F/T sensor reads the wrench that holding the door's handle takes (HoldingPlant:
// the door's own dynamics plus a known handle spring, mapped to a wrench without the
// estimator's regressor): the handle's (K, C, O) is recovered within 5 %, and the scatter that
// the sensor's noise adds lies within the filter's reported 3σ; the second-order state-variable
// filter against its closed-form step response.
#include <catch2/catch.hpp>

#include <cmath>

#include "estimation/state_variable_filter.hpp"
#include "estimation_loop_setup.hpp"

using namespace mrqp;

TEST_CASE("The state-variable filter follows the closed-form step response", "[estimation][filter]") {
  const double T = 0.004, fc = 2.0;
  estimation::StateVariableFilter f(1, T, fc);
  f.reset(Eigen::VectorXd::Zero(1));
  const double w = 2.0 * M_PI * fc, z = std::sqrt(0.5), wd = w * std::sqrt(1.0 - z * z);
  for (int k = 1; k <= 500; ++k) {
    f.step(Eigen::VectorXd::Ones(1));
    const double t = k * T;
    const double y =
        1.0 - std::exp(-z * w * t) * (std::cos(wd * t) + z / std::sqrt(1.0 - z * z) * std::sin(wd * t));
    const double yd = w / std::sqrt(1.0 - z * z) * std::exp(-z * w * t) * std::sin(wd * t);
    REQUIRE(f.value()(0) == Approx(y).margin(1e-12));
    REQUIRE(f.derivative()(0) == Approx(yd).margin(1e-10));
  }
  CHECK_THROWS_AS(estimation::StateVariableFilter(1, T, 200.0), std::invalid_argument);  // above Nyquist
  CHECK_THROWS_AS(estimation::StateVariableFilter(0, T, fc), std::invalid_argument);
}

namespace {

struct Outcome {
  Eigen::Vector3d estimate, sd, truth;
  long updates = 0;
  double fed_back_k = 0.0;
};

Outcome runDoor(double force_noise, double torque_noise) {
  const std::string text = esttest::sceneText("door_estimate.yaml");
  esttest::EstimationSetup s(text, "door_estimate.yaml", force_noise, torque_noise);
  REQUIRE(s.hook->size() == 1);
  const int handle_v = s.est.entities[0].springs[0].velocity_index;
  const auto& door = s.sc.problem->entity(s.est.entities[0].entity);
  // feed_back: the QP's model starts from the estimation's initial values, not the scene's spring.
  CHECK(door.springs()[static_cast<std::size_t>(handle_v)].stiffness == Approx(1.0));
  REQUIRE(s.boot());
  const int cycles = static_cast<int>(std::lround(10.0 / s.sc.settings.dt));
  for (int k = 0; k < cycles; ++k) s.cycle();
  REQUIRE_FALSE(s.ctrl->safeStopped());
  Outcome o;
  o.estimate = s.hook->spring(0, 0);
  o.sd = s.hook->springStd(0, 0);
  o.truth = s.est.entities[0].springs[0].truth;
  o.updates = s.hook->updates(0);
  o.fed_back_k = door.springs()[static_cast<std::size_t>(handle_v)].stiffness;
  return o;
}

}  // namespace

TEST_CASE("The handle's spring is estimated on the loop from the wrist F/T sensor", "[estimation][loop]") {
  const Outcome clean = runDoor(0.0, 0.0);
  const Outcome noisy = runDoor(0.2, 0.01);                       // the scene's plant noise
  REQUIRE(clean.truth.isApprox(Eigen::Vector3d(3.0, 0.8, 0.4)));  // the scene's door spring
  for (const Outcome* o : {&clean, &noisy}) {
    INFO("estimate " << o->estimate.transpose() << ", std " << o->sd.transpose() << ", truth "
                     << o->truth.transpose() << ", updates " << o->updates);
    CHECK(o->updates > 2000);  // 9.5 s at 250 Hz
    for (int i = 0; i < 3; ++i) CHECK(std::abs(o->estimate(i) - o->truth(i)) <= 0.05 * std::abs(o->truth(i)));
    // Fed back into the QP's model.
    CHECK(o->fed_back_k == Approx(o->estimate(0)));
  }
  // What the sensor's noise moves the estimate by is covered by the filter's 3σ.
  INFO("clean " << clean.estimate.transpose() << ", noisy " << noisy.estimate.transpose() << ", std "
                << noisy.sd.transpose());
  for (int i = 0; i < 3; ++i) {
    CHECK(noisy.sd(i) > 0.0);
    CHECK(noisy.sd(i) < 0.05 * std::abs(noisy.truth(i)));
    CHECK(std::abs(noisy.estimate(i) - clean.estimate(i)) <= 3.0 * noisy.sd(i));
  }
}
