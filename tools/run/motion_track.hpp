// The motion of a run, for people to look at first: the state of every entity of the plant at
// evenly spaced times, stored into memory sized before the loop (capture() is allocation-free and
// runs between cycles), then rendered headless after the run by the MuJoCo renderer
// (control/sim/recorder.hpp): DIR/motion.png, a strip of key frames, and DIR/motion.mp4 where
// ffmpeg exists. Whatever the plant of the run (ideal or MuJoCo), the pictures are drawn from
// its entities' states.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::run {

class MotionTrack {
 public:
  /// Room for every frame of a run of `duration` seconds at `fps` (set-up: allocates).
  MotionTrack(const loop::Plant& plant, const problem::MultiRobotProblem& problem, double duration,
              double fps);

  /// Whether the run's time t has reached the next frame.
  bool due(double t) const noexcept { return frames_ < capacity_ && t + 1e-9 >= next_; }
  /// Stores the plant's entity states as the frame of time t (no allocation).
  void capture(double t) noexcept;
  int frames() const noexcept { return frames_; }

  /// Renders the frames into `out_dir`; returns what was written, or why nothing was (a build
  /// without MuJoCo, no frame). Host-side, after the run.
  std::string render(const scene::SceneSpec& spec, const std::string& text, const std::string& file,
                     const scene::ModelRegistry& models, const std::string& out_dir) const;

 private:
  const loop::Plant& plant_;
  std::vector<std::string> names_;
  std::vector<int> handles_, nq_, nv_, offset_;
  Eigen::MatrixXd q_;       // one column per frame: every entity's q, stacked
  Eigen::VectorXd v_work_;  // velocities are read and dropped
  int capacity_ = 0, frames_ = 0;
  double fps_ = 30.0, next_ = 0.0;
};

}  // namespace mrqp::run
