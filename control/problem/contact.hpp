// A contact of the multi-robot problem (eq. 2–17): a surface given as points in a frame of one
// entity, touching either the fixed environment or a frame of another entity. One set of
// generator coefficients λ ≥ 0 describes the force on the surface entity; the other entity feels
// exactly the opposite force at the same point, so Newton's third law holds by construction
// (the reaction is never a variable of its own).
//
// A contact may leave directions free (ContactDesc::free, in its contact frame: the tangents t1,
// t2 and the normal n of contactFrame()): a free direction drops that row of the no-slip
// constraint (15–16), so the relative motion along it is left to the tasks (the admittance of
// Sec. III moves a hand along n while its contact keeps the force variables and friction cone).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace mrqp::problem {

inline constexpr int kMaxContactPoints = 8;
inline constexpr int kMaxConeGenerators = 16;

/// Directions of a contact frame (t1, t2, n) as bits of ContactDesc::free: translations then
/// rotations.
enum ContactDirection : std::uint8_t {
  kAlongT1 = 1u << 0,
  kAlongT2 = 1u << 1,
  kAlongNormal = 1u << 2,
  kAboutT1 = 1u << 3,
  kAboutT2 = 1u << 4,
  kAboutNormal = 1u << 5,
};
inline constexpr std::uint8_t kFreeNormal = kAlongNormal;          ///< slide along n
inline constexpr std::uint8_t kFreeTangent = kAlongT1 | kAlongT2;  ///< slide in the plane
inline constexpr std::uint8_t kFreeTwist = kAboutNormal;           ///< turn about n
inline constexpr std::uint8_t kFreeTilt = kAboutT1 | kAboutT2;     ///< tilt off the plane
inline constexpr std::uint8_t kFreeRotations = kAboutT1 | kAboutT2 | kAboutNormal;
inline constexpr std::uint8_t kFreeAll = 0x3f;

/// A contact with every name resolved to an index: cheap to copy, no allocation.
struct ContactDesc {
  int entity = -1;        ///< the surface's entity
  int frame = -1;         ///< the surface's frame (points and normal are in its coordinates)
  int other_entity = -1;  ///< −1: the fixed environment
  int other_frame = -1;   ///< frame of other_entity carrying the reaction
  int npoints = 0;
  std::array<Eigen::Vector3d, kMaxContactPoints> points{};
  /// Direction of the force applied ON `entity` (frame coordinates, unit).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double friction = 0.7;  ///< Coulomb μ
  int generators = 4;     ///< edges of the linearised cone per point (3 … kMaxConeGenerators)
  /// Directions left free (ContactDirection bits; 0: held in all). A point contact holds no
  /// rotation, so only its translation bits may be set.
  std::uint8_t free = 0;

  int variables() const noexcept { return npoints * generators; }
  /// Directions the no-slip constraint holds (ContactDirection bits): a point contact the three
  /// translations, a surface all six, minus the free ones.
  std::uint8_t held() const noexcept {
    return static_cast<std::uint8_t>((npoints == 1 ? 0x07 : 0x3f) & ~free);
  }
  /// Whether direction k (ContactDirection bit index 0…5) is held / left free.
  bool holds(int k) const noexcept { return ((held() >> k) & 1) != 0; }
  bool frees(int k) const noexcept { return ((free >> k) & 1) != 0; }
  /// Rows of the no-slip constraint: one per held direction (3 for a point contact, 6 for a
  /// surface, when nothing is free).
  int rows() const noexcept {
    int r = 0;
    for (std::uint8_t h = held(); h != 0; h = static_cast<std::uint8_t>(h & (h - 1))) ++r;
    return r;
  }
};

/// The contact frame of a unit normal n: columns t1, t2, n (right-handed, orthonormal), the basis
/// of coneGenerator's tangents and of ContactDesc::free.
Eigen::Matrix3d contactFrame(const Eigen::Vector3d& n) noexcept;

/// Unit edge `k` of the linearised friction cone of axis n (unit) and coefficient μ: the cone
/// {f : ‖f − (f·n)n‖ ≤ μ f·n} is approximated from inside by the pyramid spanned by
/// (n + μ(cos θk t1 + sin θk t2)) / ‖·‖, θk = 2πk/K, with t1, t2 an orthonormal basis of n⊥.
Eigen::Vector3d coneGenerator(const Eigen::Vector3d& n, double mu, int k, int K) noexcept;

/// Checks a ContactDesc against its own rules (points 1…8, generators 3…16, μ > 0, finite values,
/// non-zero normal, free directions among the six (translations only for a point contact), and for a surface of ≥ 2 points: at least 3 not on one line). Returns nullptr
/// when valid, else a static message.
const char* validateContact(const ContactDesc& c) noexcept;

}  // namespace mrqp::problem
