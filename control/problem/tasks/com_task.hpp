// CoM task: the centre of mass of one entity, or of a group of entities, to a point (world).
// For the group G with M = Σ_{i∈G} mᵢ, c = Σ mᵢ cᵢ / M and Jc = [… mᵢ/M · Jcᵢ …] (columns of each
// member's q̈); three rows (x, y, z):
//
//   Jc q̈ = c̈ʳᵉᶠ − K (c − cʳᵉᶠ) − D (Jc q̇ − ċʳᵉᶠ) − J̇c q̇                 (eq. 25–26)
#pragma once

#include <cstdint>

#include "problem/task.hpp"

namespace mrqp::problem {

class ComTask final : public Task {
 public:
  /// `entity_mask`: bit i set for entity i (one bit: one entity's CoM).
  ComTask(std::uint32_t entity_mask, const Eigen::Vector3d& target);

  const char* kind() const noexcept override { return "com"; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;
  bool setTarget(const Eigen::Vector3d& target) noexcept override;

  std::uint32_t entityMask() const noexcept { return mask_; }
  bool involves(int entity) const noexcept {
    return entity >= 0 && entity < 32 && ((mask_ >> entity) & 1u) != 0;
  }
  const Eigen::Vector3d& target() const noexcept { return target_; }

 private:
  std::uint32_t mask_;
  Eigen::Vector3d target_;
};

}  // namespace mrqp::problem
