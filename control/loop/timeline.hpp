// The timeline section of a scene file (docs/loop.md): changes to the problem at given times of
// a run — a task's weight or target, a task or a contact switched off — played by the controller
// as a cycle hook (between the estimate and the QP update). Reading resolves every name against
// the built scene (errors "FILE:LINE: FIELD: message"); playing is allocation-free.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "loop/controller.hpp"
#include "scene/scene_builder.hpp"

namespace mrqp::loop {

struct TimelineEvent {
  enum class Kind : std::uint8_t { TaskWeight = 0, TaskTarget, TaskOff, ContactOff };
  double at = 0.0;  ///< s since the first cycle
  Kind kind = Kind::TaskWeight;
  int id = -1;  ///< task or contact id
  double value = 0.0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

class Timeline final : public CycleHook {
 public:
  /// The `timeline:` section of the scene held in `text`, resolved against `scene` (empty when
  /// the scene has none). Events are played in time order (file order for equal times).
  static Timeline read(const std::string& text, const std::string& file, const scene::Scene& scene);

  void onCycle(Controller& controller, drivers::TimeNs now) noexcept override;
  const std::vector<TimelineEvent>& events() const noexcept { return events_; }
  /// Events played so far.
  std::size_t played() const noexcept { return next_; }

 private:
  std::vector<TimelineEvent> events_;
  std::size_t next_ = 0;
};

}  // namespace mrqp::loop
