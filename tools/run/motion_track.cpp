// mrqp-run's record of the motion (see motion_track.hpp).
#include "motion_track.hpp"

#include <algorithm>
#include <cmath>

#ifdef MRQP_RUN_HAVE_MUJOCO
#include "sim/mujoco_plant.hpp"
#include "sim/plant_yaml.hpp"
#include "sim/recorder.hpp"
#endif

namespace mrqp::run {

MotionTrack::MotionTrack(const loop::Plant& plant, const problem::MultiRobotProblem& problem, double duration,
                         double fps)
    : plant_(plant), fps_(fps) {
  int rows = 0, max_nv = 0;
  for (int i = 0; i < problem.entityCount(); ++i) {
    const problem::Entity& e = problem.entity(i);
    const int h = plant.entityHandle(e.name());
    if (h < 0) continue;
    names_.push_back(e.name());
    handles_.push_back(h);
    nq_.push_back(e.nq());
    nv_.push_back(e.nv());
    offset_.push_back(rows);
    rows += e.nq();
    max_nv = std::max(max_nv, e.nv());
  }
  capacity_ = static_cast<int>(std::ceil(std::max(duration, 0.0) * fps)) + 1;
  q_ = Eigen::MatrixXd::Zero(rows, capacity_);
  v_work_ = Eigen::VectorXd::Zero(max_nv);
}

void MotionTrack::capture(double t) noexcept {
  if (frames_ >= capacity_) return;
  for (std::size_t i = 0; i < handles_.size(); ++i) {
    plant_.entityState(handles_[i], q_.col(frames_).segment(offset_[i], nq_[i]), v_work_.head(nv_[i]));
  }
  ++frames_;
  next_ = t + 1.0 / fps_;
}

std::string MotionTrack::render(const scene::SceneSpec& spec, const std::string& text,
                                const std::string& file, const scene::ModelRegistry& models,
                                const std::string& out_dir) const {
  if (frames_ == 0) return "no motion recorded";
#ifdef MRQP_RUN_HAVE_MUJOCO
  sim::MujocoPlant replay(spec, sim::loadPlantSpecString(text, file), &models);
  sim::RecorderOptions o;
  o.out_dir = out_dir;
  o.fps = fps_;
  sim::Recorder recorder(replay, o);
  for (int f = 0; f < frames_; ++f) {
    for (std::size_t i = 0; i < handles_.size(); ++i) {
      const int h = replay.entityHandle(names_[i]);
      if (h < 0 || replay.entityNq(h) != nq_[i]) continue;
      replay.setEntityState(h, q_.col(f).segment(offset_[i], nq_[i]),
                            Eigen::VectorXd::Zero(replay.entityNv(h)));
    }
    recorder.capture();
  }
  const sim::RecorderOutput out = recorder.finish();
  return out.strip + " (" + std::to_string(out.frames) + " frames)" +
         (out.video.empty() ? "; " + out.note : ", " + out.video);
#else
  (void)spec;
  (void)text;
  (void)file;
  (void)models;
  (void)out_dir;
  return "no rendering: this build has no MuJoCo";
#endif
}

}  // namespace mrqp::run
