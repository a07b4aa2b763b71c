// A weighted task of the multi-robot QP (eq. 25–26), with every name resolved to an index.
// A task contributes w·‖Sel (J q̈ + J̇ q̇ − g̈ᵈ)‖² to the cost, with the PD-shaped desired
// acceleration g̈ᵈ = g̈ʳᵉᶠ − K (g − gʳᵉᶠ) − D (ġ − ġʳᵉᶠ) of eq. 26 (set-point references here, so
// ġʳᵉᶠ = g̈ʳᵉᶠ = 0) and D = 2√K (critical damping) unless given.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace mrqp::problem {

enum class TaskType : std::uint8_t {
  Posture,            ///< every joint of one entity to a reference configuration (not the base)
  Com,                ///< CoM of one entity, or of a group (entity_mask), to a point (world)
  FramePosition,      ///< a point of a frame to a world position
  FrameOrientation,   ///< a frame's orientation to a world orientation
  FramePose,          ///< both: rows (angular; linear)
  JointTarget,        ///< one joint of a mechanism to a value (e.g. a door angle)
  ContactForce,       ///< ‖f − fᵈ‖² on a contact's resultant force (world), the QP force task
  ForceMinimisation,  ///< ‖λ‖² on one contact's generators (or every contact's, contact = −1)
};

/// Dimension of the task before selection.
int taskDimension(TaskType t) noexcept;

struct TaskDesc {
  TaskType type = TaskType::Posture;
  int entity = -1;                  ///< all but group CoM and force tasks
  std::uint32_t entity_mask = 0;    ///< group CoM: bit i set for entity i (≤ 32 entities)
  int frame = -1;                   ///< frame tasks
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< controlled point, frame coordinates
  int joint = -1;                   ///< JointTarget: velocity index within the entity
  int contact = -1;                 ///< force tasks: contact id
  double weight = 1.0;
  double stiffness = 10.0;
  double damping = -1.0;            ///< < 0: critical, 2·sqrt(stiffness)
  std::array<std::uint8_t, 6> dims{{1, 1, 1, 1, 1, 1}};  ///< selector over the task's rows
  /// Position target (Com, FramePosition, FramePose), joint value (x), force (ContactForce).
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Matrix3d target_rotation = Eigen::Matrix3d::Identity();  ///< orientation tasks
};

}  // namespace mrqp::problem
