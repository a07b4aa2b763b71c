// A linear inequality Σ cₖ qₖ ≤ upper over joints of one or several entities (e.g. a door latch:
// the door cannot open until the handle is turned), kept by a velocity damper (eq. 21, 24): with
// the slack s = upper − Σ cₖ qₖ, once s < s_i (interaction),
//
//   ṡ + s̈ Δt ≥ −ξ (s − s_s)/(s_i − s_s),   s̈ = −Σ cₖ q̈ₖ
//
// i.e. −Δt Σ cₖ q̈ₖ ≥ −ξ (s − s_s)/(s_i − s_s) − ṡ. One inequality row (free while s ≥ s_i).
#pragma once

#include <array>

#include "problem/constraint.hpp"

namespace mrqp::problem {

class JointInequality final : public Constraint {
 public:
  static constexpr int kMaxTerms = 4;
  struct Term {
    int entity = -1;
    int joint = -1;  ///< velocity index within the entity
    double coeff = 1.0;
  };

  /// `terms`: 1 to kMaxTerms terms; interaction s_i > security s_s, damping ξ > 0; Δt is the problem's dt.
  JointInequality(const Term* terms, int count, double upper, double interaction, double security,
                  double damping);

  const char* kind() const noexcept override { return "joint_inequality"; }
  int inequalityRows() const noexcept override { return 1; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  void update(const MultiRobotProblem& p, ConstraintRows& rows) noexcept override;

  int termCount() const noexcept { return count_; }
  const Term& term(int k) const noexcept { return terms_[static_cast<std::size_t>(k)]; }
  double upper() const noexcept { return upper_; }
  /// Slack s of the last update.
  double slack() const noexcept { return slack_; }

 private:
  std::array<Term, kMaxTerms> terms_{};
  int count_;
  double upper_, interaction_, security_, damping_;
  double slack_ = 0.0;
};

}  // namespace mrqp::problem
