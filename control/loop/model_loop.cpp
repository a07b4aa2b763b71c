// The loop without hardware (see model_loop.hpp).
#include "loop/model_loop.hpp"

#include <chrono>

#include "loop/solution_integrator.hpp"

namespace mrqp::loop {

namespace {
std::int64_t nowNs() noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
}  // namespace

ModelLoop::ModelLoop(problem::MultiRobotProblem& problem) noexcept
    : problem_(problem), dt_(problem.settings().dt) {}

qp::QpStatus ModelLoop::cycle() noexcept {
  const std::int64_t t0 = nowNs();
  const bool updated = problem_.update() == problem::UpdateStatus::Ok;
  const std::int64_t t1 = nowNs();
  qp::QpStatus status = qp::QpStatus::InvalidInput;  // a non-finite state: nothing assembled
  if (updated) status = problem_.solve();
  const std::int64_t t2 = nowNs();
  if (updated && status == qp::QpStatus::Optimal) integrateSolution(problem_, dt_);
  const std::int64_t t3 = nowNs();
  timing_ = ModelCycleTiming{t1 - t0, t2 - t1, t3 - t2, t3 - t0};
  ++cycles_;
  return status;
}

}  // namespace mrqp::loop
