// Real time: 10,000 updates of the estimator (free box, full φ; the door's spring through the
// generated regressor) allocate nothing (counting allocator, Eigen's run-time check armed).
#include <catch2/catch.hpp>

#include <cmath>

#include "counting_allocator.hpp"
#include "door_model.hpp"
#include "estimation/inertial_estimator.hpp"
#include "model/model_traits.hpp"

MRQP_MODEL_TRAITS(door_model);

using namespace mrqp::estimation;

TEST_CASE("10,000 estimator updates allocate nothing", "[estimation][realtime]") {
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  FreeBodyRegressorModel box(g);
  EstimatorConfig c;
  c.bodies = {BodyEstimate::Full};
  InertialVector prior = InertialVector::Zero();
  prior(0) = 0.1;
  prior(4) = prior(6) = prior(9) = 1e-3;
  c.body_prior = {prior};
  c.body_prior_std = {InertialVector::Ones()};
  c.observation_covariance = 1e-2 * Eigen::MatrixXd::Identity(6, 6);
  InertialEstimator est(box, c);

  using M = door_model_model;
  GeneratedRegressorModel<M> door(g);
  EstimatorConfig cd;
  cd.bodies.assign(M::nbodies, BodyEstimate::Full);
  cd.body_prior.assign(M::nbodies, prior);
  cd.body_prior_std.assign(M::nbodies, InertialVector::Ones());
  SpringEstimate s;
  s.velocity_index = 1;
  cd.springs = {s};
  cd.observation_covariance = 1e-2 * Eigen::MatrixXd::Identity(M::nv, M::nv);
  InertialEstimator est_door(door, cd);

  Eigen::VectorXd q(7), v(6), a(6), mu(6), qd(2), vd(2), ad(2), taud(2);
  int accepted = 0;
  const long allocations = mrqp::testing::allocationsIn([&] {
    for (int k = 0; k < 10000; ++k) {
      const double t = 1e-3 * k;
      q << 0.1 * t, 0.0, 1.0, std::cos(t), 0.0, std::sin(t), 0.0;
      v << 0.3 * std::sin(t), 0.2, 0.1 * std::cos(3 * t), 0.0, 0.1, 0.0;
      a << 0.5 * std::cos(t), 0.1, -0.3 * std::sin(3 * t), 0.2, 0.0, 0.1;
      mu << 0.1, 0.2 * std::sin(t), 9.0, 0.01, 0.0, 0.02;
      accepted += est.update(q, v, a, mu) ? 1 : 0;
      qd << std::sin(t), 0.3 * std::cos(2 * t);
      vd << std::cos(t), -0.6 * std::sin(2 * t);
      ad << -std::sin(t), -1.2 * std::cos(2 * t);
      taud << 0.5 * std::sin(t), 0.2 + 0.1 * std::cos(t);
      accepted += est_door.update(qd, vd, ad, taud) ? 1 : 0;
    }
  });
  CHECK(allocations == 0);
  CHECK(accepted == 20000);
}
