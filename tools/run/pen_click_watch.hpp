// summary.json's click-pen fields (docs/scenes.md, "pen_click"): how far a pen's button went and how
// far the pen moved in the hand that holds it, measured between cycles on the plant's state (what
// the world did, not what the controller believes), with the controller's estimate of the button
// beside it for the plot.
//
// The pen is the scene's entity of model `pen` (control/model/urdf/pen.urdf), its button the joint
// `button`: the travel is that joint's position (m, positive pressed). The click needs the button
// at its stop: `button_travel_required_m` is the joint's upper limit less 0.1 mm (the last tenth of
// a millimetre of the stroke, where the mechanism latches). The hand is the entity on the other side
// of the pen's first contact; `pen_slip_m` is the largest displacement, over the run, of the pen's
// frame origin (the barrel's centre) expressed in the hand's `palm` frame (or, for a hand without
// one, the frame of that contact) from where it was at the first measurement.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::run {

class PenClickWatch {
 public:
  /// The travel needed for a click below the button's stop, m.
  static constexpr double kLatchBeforeStop = 1e-4;

  /// Finds the pen and its hand in `spec` (no pen: enabled() is false and measure() does nothing);
  /// builds a second problem of the scene for the hand's kinematics and room for `cycles`
  /// measurements (set-up: allocates; throws scene::SceneError for a pen without a `button`
  /// joint or without a contact with a hand).
  PenClickWatch(const scene::SceneSpec& spec, const scene::ModelRegistry& models,
                const problem::MultiRobotProblem& controller, const loop::Plant& plant, long cycles);

  bool enabled() const noexcept { return pen_ >= 0; }
  /// One measurement at run time t: the plant's pen and hand, the controller's button estimate
  /// (no allocation).
  void measure(double t) noexcept;

  double travelMax() const noexcept { return travel_max_; }
  double travelRequired() const noexcept { return travel_required_; }
  double slipMax() const noexcept { return slip_max_; }

  /// The summary.json fields, as (name, JSON value text).
  std::vector<std::pair<std::string, std::string>> summaryFields() const;
  /// DIR/button_travel.csv (t, plant travel, estimated travel, slip) and, with `plot`,
  /// DIR/button_travel.png (gnuplot). Returns the files written; `error` says what failed.
  std::vector<std::string> write(const std::string& dir, bool plot, std::string* error) const;

 private:
  const problem::MultiRobotProblem& controller_;
  const loop::Plant& plant_;
  scene::Scene own_;                        // the plant's state goes through this problem's kinematics
  int pen_ = -1, hand_ = -1;                // entity indices (both problems)
  int pen_handle_ = -1, hand_handle_ = -1;  // plant handles
  int button_q_ = -1, palm_frame_ = -1;
  double travel_required_ = 0.0, travel_max_ = 0.0, slip_max_ = 0.0;
  bool have_origin_ = false;
  Eigen::Vector3d origin_in_palm_ = Eigen::Vector3d::Zero();
  Eigen::VectorXd pen_q_, pen_v_, hand_q_, hand_v_;
  std::vector<double> t_, travel_, estimate_, slip_;
  std::size_t count_ = 0;
};

}  // namespace mrqp::run
