// The floating base's estimate against the plant's truth (docs/loop.md, "The cycle"): JVRC-1's
// pelvis IMU with a gyro bias, gyro noise and attitude noise, fused with the kinematics of the
// feet on the ground by the complementary filter (loop::BaseAttitudeFilter). The estimated base
// orientation stays far closer to the truth than the IMU's own attitude output, the position
// (fitted to the feet with that orientation) within millimetres, and the filter learns the bias.
// The filter alone is checked against closed forms: a constant rate integrates exactly, and a
// constant bias is learnt with the error dynamics ë + k_p ė + k_i e = 0.
#include <catch2/catch.hpp>

#include <cmath>

#include "loop/base_attitude_filter.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

}  // namespace

TEST_CASE("loop: base attitude filter: exact rate integration and bias learning", "[loop][base]") {
  using loop::BaseAttitudeFilter;
  SECTION("a constant rate with the reference moving along: no error, the rotation of the closed form") {
    BaseAttitudeFilter f;
    const Eigen::Vector3d w(0.3, -0.2, 0.5);
    const double T = 0.01;
    f.reset(Eigen::Quaterniond::Identity());
    for (int k = 1; k <= 100; ++k) {
      const Eigen::Quaterniond truth(Eigen::AngleAxisd(w.norm() * k * T, w.normalized()));
      f.update(w, T, truth, true);
    }
    const Eigen::Quaterniond closed(Eigen::AngleAxisd(w.norm() * 1.0, w.normalized()));
    CHECK(angleBetween(f.orientation(), closed) < 1e-9);
    CHECK(f.bias().norm() < 1e-9);
  }
  SECTION("a constant gyro bias at rest is learnt; the orientation error stays bounded") {
    loop::AttitudeFilterGains g;
    BaseAttitudeFilter f(g);
    const Eigen::Vector3d bias(0.03, -0.02, 0.01);
    const double T = 0.001;
    f.reset(Eigen::Quaterniond::Identity());
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      f.update(bias, T, Eigen::Quaterniond::Identity(), true);
      worst = std::max(worst, angleBetween(f.orientation(), Eigen::Quaterniond::Identity()));
    }
    // Critically damped (k_i = k_p²/4): e(t) = |b| t e^{−k_p t / 2}, largest at t = 2/k_p.
    const double peak = bias.norm() * (2.0 / g.kp_contacts) * std::exp(-1.0);
    INFO("worst " << worst << ", closed form " << peak);
    CHECK(worst == Approx(peak).epsilon(0.05));
    CHECK((f.bias() - bias).norm() < 1e-3 * bias.norm());
  }
}

TEST_CASE("loop: JVRC-1's base from a biased, noisy IMU fused with the feet's kinematics", "[loop][base]") {
  LoopSetup s(looptest::sceneText("jvrc1_box.yaml"), "jvrc1_box.yaml");
  loop::PlantImu* imu = s.rig->imu("");
  REQUIRE(imu != nullptr);
  loop::ImuNoise noise;
  noise.gyro_bias = Eigen::Vector3d(0.03, -0.02, 0.01);
  noise.gyro_noise = 0.005;
  noise.attitude_noise = 0.01;
  imu->setNoise(noise);
  REQUIRE(s.boot());
  problem::MultiRobotProblem& p = *s.sc.problem;
  const int e = p.entityIndex("jvrc");
  const int h = s.plant->entityHandle("jvrc");
  const problem::Entity& en = p.entity(e);
  Eigen::VectorXd q(en.nq()), v(en.nv());
  const int imu_frame = s.plant->frameHandle("jvrc", s.hw.robots.at(0).imus.at(0).frame_name);
  double worst_angle = 0.0, worst_pos = 0.0, sum_imu = 0.0;
  int samples = 0;
  const int divisor = s.hw.robots.at(0).divisor;
  for (int k = 0; k < 2000; ++k) {
    s.cycle();
    if (k < 500 || (k - 1) % divisor != 0) continue;  // after the filter's settling, after each robot cycle
    s.plant->entityState(h, q, v);
    const Eigen::Quaterniond truth(q(3), q(4), q(5), q(6));
    const auto qe = en.q();
    const Eigen::Quaterniond est(qe(3), qe(4), qe(5), qe(6));
    worst_angle = std::max(worst_angle, angleBetween(truth, est));
    worst_pos = std::max(worst_pos, (q.head<3>() - qe.head<3>()).norm());
    const drivers::ImuFeedback& m = s.ctrl->robots().at(0).imu.at(0);
    const Eigen::Quaterniond imu_att(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
    sum_imu += angleBetween(imu_att, s.plant->imu(imu_frame).orientation);  // the truth of the IMU frame
    ++samples;
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  REQUIRE(samples > 100);
  const double imu_mean = sum_imu / samples;
  INFO("estimate vs truth: worst angle " << worst_angle << " rad, worst position " << worst_pos
                                         << " m; the IMU's attitude output is off by " << imu_mean
                                         << " rad on average");
  CHECK(imu_mean > 0.01);  // the attitude noise is there (σ = 0.01 rad per axis)
  CHECK(worst_angle < 0.2 * imu_mean);
  CHECK(worst_pos < 2e-3);
  // The bias is learnt in base axes: the IMU's bias turned by the IMU frame's orientation in the base.
  const problem::Pose pelvis = en.framePose(s.hw.robots.at(0).imus.at(0).frame);
  const auto qe = en.q();
  const Eigen::Matrix3d R_base_imu =
      Eigen::Quaterniond(qe(3), qe(4), qe(5), qe(6)).toRotationMatrix().transpose() * pelvis.R;
  const Eigen::Vector3d bias = s.ctrl->estimator()->gyroBias(e);
  INFO("bias estimate " << bias.transpose() << ", true " << (R_base_imu * noise.gyro_bias).transpose());
  CHECK((bias - R_base_imu * noise.gyro_bias).norm() < 0.2 * noise.gyro_bias.norm());
}
