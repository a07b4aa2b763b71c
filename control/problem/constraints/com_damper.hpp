// The CoM support-region damper of one entity (paper 2, eq. 7): the horizontal CoM c stays inside
// the convex hull of the entity's contact points with the environment. For each edge i of the
// hull, with inward normal aᵢ and distance dᵢ = aᵢᵀc − bᵢ, once dᵢ < d_i (interaction distance):
//
//   ḋᵢ + d̈ᵢ Δt ≥ −ξ (dᵢ − d_s)/(d_i − d_s),   d̈ᵢ = aᵢᵀ (Jc q̈ + J̇c q̇)_xy
//
// i.e. Δt aᵢᵀ Jc,xy q̈ ≥ −ξ (dᵢ − d_s)/(d_i − d_s) − aᵢᵀ ċ_xy − Δt aᵢᵀ (J̇c q̇)_xy.
// kRows inequality rows are reserved (one per edge); edges beyond stay free.
#pragma once

#include "problem/constraint.hpp"
#include "problem/support_polygon.hpp"

namespace mrqp::problem {

class ComDamper final : public Constraint {
 public:
  static constexpr int kRows = 16;

  /// interaction d_i > security d_s ≥ 0 (m), damping ξ > 0 (m/s); Δt is the problem's dt.
  ComDamper(int entity, double interaction, double security, double damping);

  const char* kind() const noexcept override { return "com_damper"; }
  int inequalityRows() const noexcept override { return kRows; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  void update(const MultiRobotProblem& p, ConstraintRows& rows) noexcept override;

  int entity() const noexcept { return entity_; }
  /// The support region of the last update.
  const SupportPolygon& polygon() const noexcept { return polygon_; }

 private:
  int entity_;
  double interaction_, security_, damping_;
  SupportPolygon polygon_;
};

}  // namespace mrqp::problem
