// Force minimisation task: ‖λ‖² over one contact's cone generators, or over every contact's
// (contact < 0). Identity rows over those λ with a zero target:
//
//   λ = 0
//
// Gains, selection and references do not enter.
#pragma once

#include "problem/task.hpp"

namespace mrqp::problem {

class ForceMinTask final : public Task {
 public:
  /// `contact` < 0: every contact.
  explicit ForceMinTask(int contact = -1);

  const char* kind() const noexcept override { return "force_min"; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;

  int contact() const noexcept { return contact_; }

 private:
  int contact_;
};

}  // namespace mrqp::problem
