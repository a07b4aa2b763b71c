// A controller loop for the estimation tests: a scene (text) with its hardware and estimation
// sections, the ideal plant wrapped by a plant whose F/T sensor reads what a hand holding the
// door's handle must apply, the simulated buses with the emulated firmware, the controller, the
// scene's timeline and the estimator hook.
//
// The wrench (HoldingPlant) is computed from the plant's own state, independently of the
// estimator's regressor: the door's generalised force τ = M(q) q̈ + N(q, q̇) + K q + C q̇ + O on the
// handle (the door's RNEA through its mass matrix and bias on a problem of its own; q̈ the plant's
// own acceleration, the difference of its velocities over its last step), as the minimum-norm
// wrench w = J (Jᵀ J)⁻¹ τ at the sensor's origin (J the door's world-aligned Jacobian of that
// point of the handle), read by the sensor as the tool side's wrench on the arm with the weight
// of the tool (the hand: the estimation section's tool mass and CoM) added: f_s = Rᵀ (m g − f),
// τ_s = Rᵀ ((R c) × m g − τ), plus an optional Gaussian noise.
#pragma once

#include <Eigen/Cholesky>

#include <memory>
#include <random>
#include <string>

#include "estimation/estimation_yaml.hpp"
#include "estimation/estimator_hook.hpp"
#include "loop/controller.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "loop/ideal_plant.hpp"
#include "loop/timeline.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

namespace esttest {

using namespace mrqp;

inline std::string sceneText(const std::string& name) {
  return scene::readTextFile(std::string(MRQP_SCENES_DIR) + "/" + name);
}

class HoldingPlant final : public loop::Plant {
 public:
  HoldingPlant(std::unique_ptr<loop::IdealPlant> inner, std::unique_ptr<problem::MultiRobotProblem> mirror,
               const Eigen::Vector3d& spring, double force_noise, double torque_noise)
      : inner_(std::move(inner)),
        mirror_(std::move(mirror)),
        spring_(spring),
        fn_(force_noise),
        tn_(torque_noise) {
    door_ = mirror_->entityIndex("door");
    panda_ = mirror_->entityIndex("panda");
    door_h_ = inner_->entityHandle("door");
    panda_h_ = inner_->entityHandle("panda");
    handle_frame_ = mirror_->entity(door_).frameIndex("handle");
    handle_v_ = mirror_->entity(door_).jointOffset() + mirror_->entity(door_).jointIndex("handle");
    problem::Entity& d = mirror_->entity(door_);
    for (int k = 0; k < d.nv(); ++k) (void)d.setSpring(k, problem::JointSpring{});  // N without springs
    qd_.resize(d.nq());
    vd_.resize(d.nv());
    v_prev_ = Eigen::VectorXd::Zero(d.nv());
    a_ = Eigen::VectorXd::Zero(d.nv());
    qp_.resize(mirror_->entity(panda_).nq());
    vp_.resize(mirror_->entity(panda_).nv());
    J_.resize(6, d.nv());
    tau_.resize(d.nv());
  }
  loop::IdealPlant& inner() { return *inner_; }
  double tool_mass = 0.0;
  Eigen::Vector3d tool_com = Eigen::Vector3d::Zero();

  const char* kind() const noexcept override { return "holding"; }
  int entityHandle(const std::string& entity) const override { return inner_->entityHandle(entity); }
  int jointHandle(const std::string& e, const std::string& j) const override {
    return inner_->jointHandle(e, j);
  }
  int frameHandle(const std::string& e, const std::string& f) const override {
    sensor_frame_ = mirror_->entity(mirror_->entityIndex(e)).frameIndex(f);
    return inner_->frameHandle(e, f);
  }
  double jointPosition(int j) const noexcept override { return inner_->jointPosition(j); }
  double jointVelocity(int j) const noexcept override { return inner_->jointVelocity(j); }
  double jointTorque(int j) const noexcept override { return inner_->jointTorque(j); }
  void setServo(int j, const loop::ServoCommand& c) noexcept override { inner_->setServo(j, c); }
  loop::ImuSample imu(int f) const noexcept override { return inner_->imu(f); }
  void step(double dt) noexcept override {
    inner_->entityState(door_h_, qd_, v_prev_);
    inner_->step(dt);
    inner_->entityState(door_h_, qd_, vd_);
    a_ = (vd_ - v_prev_) / dt;
  }
  double time() const noexcept override { return inner_->time(); }
  void entityState(int e, Eigen::Ref<Eigen::VectorXd> q,
                   Eigen::Ref<Eigen::VectorXd> v) const noexcept override {
    inner_->entityState(e, q, v);
  }

  loop::Vector6d sensorWrench(int) const noexcept override {
    problem::Entity& d = mirror_->entity(door_);
    problem::Entity& p = mirror_->entity(panda_);
    inner_->entityState(door_h_, qd_, vd_);
    inner_->entityState(panda_h_, qp_, vp_);
    d.q() = qd_;
    d.v() = vd_;
    d.update();
    p.q() = qp_;
    p.v() = vp_;
    p.update();
    tau_.noalias() = d.massMatrix() * a_;
    tau_ += d.bias();
    tau_(handle_v_) += spring_(0) * qd_(handle_v_) + spring_(1) * vd_(handle_v_) + spring_(2);
    const problem::Pose sensor = p.framePose(sensor_frame_);
    const problem::Pose handle = d.framePose(handle_frame_);
    d.frameJacobian(handle_frame_, handle.R.transpose() * (sensor.p - handle.p), J_);
    const Eigen::Matrix2d JtJ = J_.transpose() * J_;
    const Eigen::Matrix<double, 6, 1> w = J_ * JtJ.ldlt().solve(tau_.head<2>());
    loop::Vector6d out;
    const Eigen::Vector3d weight = tool_mass * Eigen::Vector3d(0.0, 0.0, -9.81);
    out.head<3>() = sensor.R.transpose() * (weight - w.tail<3>());
    out.tail<3>() = sensor.R.transpose() * ((sensor.R * tool_com).cross(weight) - w.head<3>());
    for (int i = 0; i < 3; ++i) {
      out(i) += fn_ * normal_(rng_);
      out(i + 3) += tn_ * normal_(rng_);
    }
    return out;
  }

 private:
  std::unique_ptr<loop::IdealPlant> inner_;
  std::unique_ptr<problem::MultiRobotProblem> mirror_;
  Eigen::Vector3d spring_;
  double fn_, tn_;
  int door_ = -1, panda_ = -1, door_h_ = -1, panda_h_ = -1, handle_frame_ = -1, handle_v_ = -1;
  mutable int sensor_frame_ = -1;
  mutable Eigen::VectorXd qd_, vd_, qp_, vp_, tau_;
  Eigen::VectorXd v_prev_, a_;
  mutable Eigen::MatrixXd J_;
  mutable std::mt19937_64 rng_{7};
  mutable std::normal_distribution<double> normal_{0.0, 1.0};
};

struct EstimationSetup {
  EstimationSetup(const std::string& text, const std::string& file, double force_noise = 0.0,
                  double torque_noise = 0.0) {
    scene::addBuiltinModels(models);
    spec = scene::loadSceneString(text, file);
    sc = scene::buildScene(spec, models);
    hw = loop::resolveHardware(loop::readHardwareString(text, file), *sc.problem, sc.settings.dt);
    est = estimation::readEstimation(text, file, spec, sc, hw);
    auto ideal = std::make_unique<loop::IdealPlant>(scene::buildScene(spec, models).problem, *sc.problem);
    plant = std::make_unique<HoldingPlant>(std::move(ideal), scene::buildScene(spec, models).problem,
                                           est.entities.at(0).springs.at(0).truth, force_noise, torque_noise);
    plant->tool_mass = est.entities.at(0).hands.at(0).tool_mass;
    plant->tool_com = est.entities.at(0).hands.at(0).tool_com;
    rig = std::make_unique<loop::EmulatedRig>(hw, *sc.problem, *plant);
    std::vector<drivers::Bus*> buses;
    for (std::size_t b = 0; b < rig->busCount(); ++b) buses.push_back(&rig->master(b));
    ctrl = std::make_unique<loop::Controller>(*sc.problem, hw, buses);
    period = static_cast<drivers::TimeNs>(std::llround(sc.settings.dt * 1e9));
    timeline = std::make_unique<loop::Timeline>(loop::Timeline::read(text, file, sc));
    ctrl->addHook(*timeline);
    hook = std::make_unique<estimation::EstimatorHook>(*ctrl, est);
    ctrl->addHook(*hook);
  }

  bool boot() {
    ctrl->startDevices(now);
    for (int k = 0; k < 10000; ++k) {
      const bool ready = ctrl->bootCycle(now);
      rig->advanceTo(now + period);
      now += period;
      if (ready) return true;
    }
    return false;
  }

  void cycle() noexcept {
    ctrl->cycle(now);
    plant->inner().setFollowing(!ctrl->safeStopped());
    rig->advanceTo(now + period);
    now += period;
  }

  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene sc;
  loop::ResolvedHardware hw;
  estimation::EstimationSpec est;
  std::unique_ptr<HoldingPlant> plant;
  std::unique_ptr<loop::EmulatedRig> rig;
  std::unique_ptr<loop::Controller> ctrl;
  std::unique_ptr<loop::Timeline> timeline;
  std::unique_ptr<estimation::EstimatorHook> hook;
  drivers::TimeNs now = 0;
  drivers::TimeNs period = 1000000;
};

}  // namespace esttest
