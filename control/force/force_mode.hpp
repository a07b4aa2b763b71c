// The switch configurations of Fig. 4 (Sec. III) as modes of one end-effector's force control
// (docs/force-control.md). Switch 2 picks the target force of the admittance: up, the force the QP
// computed for the end-effector's contact; down, the user's force fᵈ. Switch 1 closed also gives
// fᵈ to the QP as a force task (the cost term ‖f − fᵈ‖², "QP force task").
//
//   mode         switch 1   switch 2   admittance target   QP force task
//   autonomous   open       up         QP contact force    no
//   direct       open       down       fᵈ                  no
//   qp           closed     up         QP contact force    fᵈ
//   guided       closed     down       fᵈ                  fᵈ
//   off          —          —          none: holds         no
#pragma once

#include <cstdint>
#include <cstring>

namespace mrqp::force {

enum class ForceMode : std::uint8_t { Off = 0, Autonomous, Direct, Qp, Guided };

/// Switch 1 closed: fᵈ is also a force task of the QP.
constexpr bool forceTaskOn(ForceMode m) noexcept { return m == ForceMode::Qp || m == ForceMode::Guided; }
/// Switch 2 up: the admittance tracks the QP's own contact force.
constexpr bool targetFromQp(ForceMode m) noexcept { return m == ForceMode::Autonomous || m == ForceMode::Qp; }
/// The mode uses fᵈ (as the admittance's target or as a QP force task).
constexpr bool usesUserForce(ForceMode m) noexcept {
  return m == ForceMode::Direct || m == ForceMode::Qp || m == ForceMode::Guided;
}

inline const char* forceModeName(ForceMode m) noexcept {
  switch (m) {
    case ForceMode::Autonomous:
      return "autonomous";
    case ForceMode::Direct:
      return "direct";
    case ForceMode::Qp:
      return "qp";
    case ForceMode::Guided:
      return "guided";
    case ForceMode::Off:
      break;
  }
  return "off";
}

/// The mode of a name as written in scene files; false when there is none.
inline bool parseForceMode(const char* name, ForceMode* out) noexcept {
  for (ForceMode m :
       {ForceMode::Off, ForceMode::Autonomous, ForceMode::Direct, ForceMode::Qp, ForceMode::Guided}) {
    if (std::strcmp(name, forceModeName(m)) == 0) {
      *out = m;
      return true;
    }
  }
  return false;
}

}  // namespace mrqp::force
