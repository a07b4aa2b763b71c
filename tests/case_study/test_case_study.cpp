// Sec. II-C against its closed forms: one multi-robot QP follows eq. 43–44, the best decoupled
// scheme eq. 40–41, and the parallel decoupled scheme breaks Newton's third law.
#include <catch2/catch.hpp>

#include <cmath>

#include "case_study.hpp"

using namespace mrqp::case_study;

TEST_CASE("at t = 0 each scheme decides what the paper says", "[case_study]") {
  CaseStudy study;
  const BoxState s0;  // (0, 0): g̈d = 1
  const Decision all = study.multiRobot(s0);
  REQUIRE(all.ok);
  CHECK(all.qdd31 == Approx(1.0).epsilon(1e-6));  // eq. 43 at t = 0
  CHECK(all.tau11 + all.tau21 == Approx(1.0).epsilon(1e-6));
  CHECK(std::abs(all.tau11) <= 0.5 + 1e-9);
  CHECK(std::abs(all.tau21) <= 0.5 + 1e-9);
  CHECK(all.newtonViolation() == 0.0);
  const Decision seq = study.sequential(s0);
  REQUIRE(seq.ok);
  CHECK(seq.qdd31 == Approx(0.5).epsilon(1e-9));  // saturated, eq. 40
  CHECK(seq.f23 == Approx(0.0).margin(1e-9));     // robot 2 only follows
  const Decision par = study.parallel(s0);
  REQUIRE(par.ok);
  CHECK(par.qdd31 == Approx(1.0).epsilon(1e-6));
  CHECK(par.f13 == Approx(0.5).epsilon(1e-6));  // the box's QP splits the force (eq. 33)...
  CHECK(par.f31 == Approx(0.0).margin(1e-6));   // ...the robots' QPs apply none (eq. 31)
  CHECK(par.newtonViolation() > 0.49);
}

TEST_CASE("integrated over 10 s both schemes match their closed forms to 1e-3", "[case_study]") {
  CaseStudy study;
  BoxState all, seq;
  const double dt = 1e-3;
  double errAll = 0, errSeq = 0;
  for (int k = 1; k <= 10000; ++k) {
    REQUIRE(rk4Step(all, dt, [&](const BoxState& x) { return study.multiRobot(x); }));
    REQUIRE(rk4Step(seq, dt, [&](const BoxState& x) { return study.sequential(x); }));
    errAll = std::max(errAll, std::abs(all.q - analyticMultiRobotPosition(k * dt)));
    errSeq = std::max(errSeq, std::abs(seq.q - analyticSequentialPosition(k * dt)));
  }
  CHECK(errAll < 1e-3);
  CHECK(errSeq < 1e-3);
  // the multi-robot QP is better: it reaches the goal faster
  CHECK(analyticMultiRobotPosition(2.0) > analyticSequentialPosition(2.0));
  CHECK(all.q == Approx(1.0).margin(1e-3));
}

TEST_CASE("the closed forms are continuous at the end of saturation, t = sqrt(6) - 2", "[case_study]") {
  const double t0 = std::sqrt(6.0) - 2.0, h = 1e-9;
  CHECK(analyticSequentialPosition(t0 - h) == Approx(analyticSequentialPosition(t0 + h)).epsilon(1e-7));
  CHECK(analyticSequentialAcceleration(t0 + h) == Approx(0.5).epsilon(1e-6));
  // eq. 44 solves q̈ = −2q̇ − q + 1 from rest at 0: check the ODE by differences
  const double t = 1.3, d = 1e-4;
  const double q = analyticMultiRobotPosition(t);
  const double qd = (analyticMultiRobotPosition(t + d) - analyticMultiRobotPosition(t - d)) / (2 * d);
  CHECK(analyticMultiRobotAcceleration(t) == Approx(-2 * qd - q + 1).epsilon(1e-6));
}
