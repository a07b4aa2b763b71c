// The loop without hardware (docs/loop.md, "Without hardware: mrqp-scene"): a scene run on its
// own models, the problem as its own plant. Each cycle updates and solves the multi-robot problem
// and, when the QP is Optimal, advances every entity by its q̈ over the period
// (integrateSolution, solution_integrator.hpp); the phases are timed. The controller loop with
// drives (Controller) does the same between its read/estimate and its write. noexcept and
// allocation-free after construction.
#pragma once

#include <cstdint>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::loop {

struct ModelCycleTiming {
  std::int64_t update_ns = 0;
  std::int64_t solve_ns = 0;
  std::int64_t integrate_ns = 0;
  std::int64_t total_ns = 0;
};

class ModelLoop {
 public:
  /// Runs `problem` at its settings' period.
  explicit ModelLoop(problem::MultiRobotProblem& problem) noexcept;

  /// One cycle: update, solve and, when Optimal, the state advanced over the period. A failed
  /// update or solve leaves the state where it was. Returns the QP's status (not Optimal also
  /// when the update failed).
  qp::QpStatus cycle() noexcept;

  problem::MultiRobotProblem& problem() noexcept { return problem_; }
  double period() const noexcept { return dt_; }
  /// Simulated time of the next cycle: cycles() × period.
  double time() const noexcept { return static_cast<double>(cycles_) * dt_; }
  std::uint64_t cycles() const noexcept { return cycles_; }
  const ModelCycleTiming& lastTiming() const noexcept { return timing_; }

 private:
  problem::MultiRobotProblem& problem_;
  double dt_;
  std::uint64_t cycles_ = 0;
  ModelCycleTiming timing_;
};

}  // namespace mrqp::loop
