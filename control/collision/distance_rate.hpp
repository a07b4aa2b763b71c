// The second time derivative of the distance between two moving convex shapes (docs/collision.md,
// "The row's d̈"): the part of d̈ that the witness points' accelerations do not carry.
//
// With a, b the witness points (on the surfaces), n = (b − a)/‖b − a‖ and acc_X(p) the
// acceleration of the material point of body X at p (what J q̈ + J̇ v gives at p):
//
//   d̈ = nᵀ(acc_B(b) − acc_A(a)) + c,
//   c = ṅᵀ(ḃ − ȧ) + nᵀ(ω_B × s_B − ω_A × s_A)   (ṅ: the normal turning; s: the witnesses sliding)
//
// computed on the polytope cores through GJK's final simplex (distance.hpp): the core witnesses
// are a_c = Σ λ_i a_i, b_c = Σ λ_i b_i over the simplex's vertex pairs, x = b_c − a_c is the
// closest point of the affine hull of w_i = b_i − a_i to the origin, so with E = [w_j − w_0],
// μ = (λ_1 … λ_m): EᵀE μ = −Eᵀ w_0, and differentiating,
//
//   EᵀE μ̇ = −Ėᵀ x − Eᵀ(ẇ_0 + Ė μ),   ẋ = E μ̇ + ẇ_0 + Ė μ,
//   L = ‖x‖:  L̈ = nᵀ(acc_B(b_c) − acc_A(a_c)) + 2 Σ λ̇_i nᵀẇ_i + (‖ẋ‖² − (nᵀẋ)²)/L,
//
// (Σ λ̈_i nᵀw_i = 0: nᵀw_i is the same for every i). Moving from the core witnesses to the surface
// ones (a = a_c + r_A n, b = b_c − r_B n) adds r_A((ω_A·n)² − ‖ω_A‖²) + r_B((ω_B·n)² − ‖ω_B‖²).
// Where the closest features change (the simplex's face changes) d is not twice differentiable;
// the value is then that of the features GJK ended on (a one-sided derivative). Penetrating
// results (libccd's MPR) have no simplex: c = 0 there.
//
// Real-time: noexcept, allocation-free (fixed-size Eigen only).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "collision/distance.hpp"

namespace mrqp::collision {

/// The velocity field of a rigid body: angular velocity ω and the velocity `v` of the point `at`
/// (world coordinates); a point p moves at v + ω × (p − at).
struct RigidMotion {
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d at = Eigen::Vector3d::Zero();

  Eigen::Vector3d velocityOf(const Eigen::Vector3d& p) const noexcept { return v + omega.cross(p - at); }
};

/// The term c of d̈ above for a separated result `r` of distance(A, B) whose shapes have radii
/// `radius_a`, `radius_b`, body A moving with `ma` and body B with `mb`. 0 for a penetrating result.
///
/// `step` > 0: c as a prediction over a step of that length. The sliding part of c is
/// −f_ss λ̇² (f: the distance of the simplex's points as a function of their barycentric
/// coordinates), which grows without bound as the closest features turn parallel (two capsules
/// side by side: f_ss → 0, λ̇ → ∞) although the witnesses then reach the end of their feature
/// within a fraction of the step. Where some λ_i + λ̇_i step would leave [0, 1], λ̇ is scaled by
/// s < 1 so that it does not: the sliding part becomes f_ss λ̇² (s² − 2s), the minimum of the
/// second-order model of f over the step with the witnesses kept on their simplex, instead of its
/// unconstrained minimum. 0 (the default): the instantaneous value.
double distanceCurvature(const DistanceResult& r, double radius_a, double radius_b, const RigidMotion& ma,
                         const RigidMotion& mb, double step = 0.0) noexcept;

}  // namespace mrqp::collision
