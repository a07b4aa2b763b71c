// A controller loop for the force-control tests: a scene (text) with its hardware and
// force_control sections, the ideal plant wrapped by a plant whose F/T sensors read a virtual
// wall, the simulated buses with the emulated firmware, the controller and the admittance hook.
//
// The wall (WallPlant) is the plane z = height of the world, below the tool: while a frame of the
// plant's entity (the contact frame) is below the plane it pushes it up with k × depth. The F/T
// sensor reads what a wrist sensor reads (loop/plant.hpp: the wrench the tool side exerts on the
// arm side, sensor axes): the wall's force plus the tool's weight m g, rotated into the sensor
// frame's axes by the plant's own kinematics (a problem of its own, posed at the plant's state).
#pragma once

#include <memory>
#include <string>

#include "force/admittance_hook.hpp"
#include "force/force_control_yaml.hpp"
#include "loop/controller.hpp"
#include "loop/device_lifecycle.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "loop/ideal_plant.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

namespace forcetest {

using namespace mrqp;

inline std::string dataText(const std::string& name) {
  return scene::readTextFile(std::string(MRQP_FORCE_TEST_DATA_DIR) + "/" + name);
}

/// Replaces the first `from` of `text` by `to` (the test scenes' variants).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class WallPlant final : public loop::Plant {
 public:
  WallPlant(std::unique_ptr<loop::IdealPlant> inner, std::unique_ptr<problem::MultiRobotProblem> mirror,
            const std::string& entity, const std::string& contact_frame)
      : inner_(std::move(inner)), mirror_(std::move(mirror)) {
    entity_ = mirror_->entityIndex(entity);
    handle_ = inner_->entityHandle(entity);
    contact_frame_ = mirror_->entity(entity_).frameIndex(contact_frame);
    q_.resize(mirror_->entity(entity_).nq());
    v_.resize(mirror_->entity(entity_).nv());
  }

  double height = -1e9;     ///< m: the wall's plane (far below: no wall)
  double stiffness = 4000;  ///< N/m
  double tool_mass = 0.0;   ///< kg: weight the sensor carries besides the wall's force
  loop::IdealPlant& inner() { return *inner_; }
  /// The wall's force on the tool (world z, N) at the last sample.
  double wallForce() const { return wall_force_; }
  /// The contact frame's height at the last sample.
  double contactHeight() const { return contact_z_; }

  const char* kind() const noexcept override { return "wall"; }
  int entityHandle(const std::string& entity) const override { return inner_->entityHandle(entity); }
  int jointHandle(const std::string& e, const std::string& j) const override {
    return inner_->jointHandle(e, j);
  }
  int frameHandle(const std::string& e, const std::string& f) const override {
    frames_.push_back({inner_->frameHandle(e, f), mirror_->entity(mirror_->entityIndex(e)).frameIndex(f)});
    return static_cast<int>(frames_.size()) - 1;
  }
  double jointPosition(int j) const noexcept override { return inner_->jointPosition(j); }
  double jointVelocity(int j) const noexcept override { return inner_->jointVelocity(j); }
  double jointTorque(int j) const noexcept override { return inner_->jointTorque(j); }
  void setServo(int j, const loop::ServoCommand& c) noexcept override { inner_->setServo(j, c); }
  loop::ImuSample imu(int f) const noexcept override {
    return inner_->imu(frames_[static_cast<std::size_t>(f)].inner);
  }
  void step(double dt) noexcept override { inner_->step(dt); }
  double time() const noexcept override { return inner_->time(); }
  void entityState(int e, Eigen::Ref<Eigen::VectorXd> q,
                   Eigen::Ref<Eigen::VectorXd> v) const noexcept override {
    inner_->entityState(e, q, v);
  }

  loop::Vector6d sensorWrench(int f) const noexcept override {
    problem::Entity& e = mirror_->entity(entity_);
    inner_->entityState(handle_, q_, v_);
    e.q() = q_;
    e.v() = v_;
    e.update();
    contact_z_ = e.framePose(contact_frame_).p.z();
    wall_force_ = contact_z_ < height ? stiffness * (height - contact_z_) : 0.0;
    const Eigen::Vector3d reading =
        Eigen::Vector3d(0.0, 0.0, wall_force_) + tool_mass * Eigen::Vector3d(0, 0, -9.81);
    const Eigen::Matrix3d R = e.framePose(frames_[static_cast<std::size_t>(f)].mirror).R;
    loop::Vector6d w = loop::Vector6d::Zero();
    w.head<3>() = R.transpose() * reading;
    return w;
  }

 private:
  struct Frame {
    int inner = -1;
    int mirror = -1;
  };
  std::unique_ptr<loop::IdealPlant> inner_;
  std::unique_ptr<problem::MultiRobotProblem> mirror_;
  int entity_ = -1, handle_ = -1, contact_frame_ = -1;
  mutable std::vector<Frame> frames_;
  mutable Eigen::VectorXd q_, v_;
  mutable double wall_force_ = 0.0, contact_z_ = 0.0;
};

struct ForceSetup {
  /// `contact_frame`: the frame of `entity` that meets the wall.
  ForceSetup(const std::string& text, const std::string& file, bool disabled = false,
             const std::string& entity = "panda", const std::string& contact_frame = "panda_hand_tcp") {
    scene::addBuiltinModels(models);
    spec = scene::loadSceneString(text, file);
    sc = scene::buildScene(spec, models);
    hw = loop::resolveHardware(loop::readHardwareString(text, file), *sc.problem, sc.settings.dt);
    auto ideal = std::make_unique<loop::IdealPlant>(scene::buildScene(spec, models).problem, *sc.problem);
    plant = std::make_unique<WallPlant>(std::move(ideal), scene::buildScene(spec, models).problem, entity,
                                        contact_frame);
    rig = std::make_unique<loop::EmulatedRig>(hw, *sc.problem, *plant);
    std::vector<drivers::Bus*> buses;
    for (std::size_t b = 0; b < rig->busCount(); ++b) buses.push_back(&rig->master(b));
    ctrl = std::make_unique<loop::Controller>(*sc.problem, hw, buses);
    period = static_cast<drivers::TimeNs>(std::llround(sc.settings.dt * 1e9));
    fc = force::readForceControl(text, file, sc, hw, sc.settings.dt);
    hook = std::make_unique<force::AdmittanceHook>(*ctrl, fc, disabled);
    ctrl->addHook(*hook);
  }

  bool boot() { return loop::bootDevices(*ctrl, now, period, rig.get()).done; }

  void cycle() noexcept {
    ctrl->cycle(now);
    plant->inner().setFollowing(!ctrl->safeStopped());
    rig->advanceTo(now + period);
    now += period;
  }

  double t() const { return static_cast<double>(ctrl->cycles()) * sc.settings.dt; }

  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene sc;
  loop::ResolvedHardware hw;
  std::unique_ptr<WallPlant> plant;
  std::unique_ptr<loop::EmulatedRig> rig;
  std::unique_ptr<loop::Controller> ctrl;
  force::ForceControlSpec fc;
  std::unique_ptr<force::AdmittanceHook> hook;
  drivers::TimeNs now = 0;
  drivers::TimeNs period = 1000000;
};

}  // namespace forcetest
