// Checks of a solved multi-robot problem that do not trust the assembly: each entity's equation
// of motion (eq. 1) is re-evaluated from the entity's own model with the reported q̈, τ and
// contact wrenches, and each contact point's force is tested against the exact Coulomb cone.
#pragma once

#include <Eigen/Core>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::testing {

/// max over entities of ‖M q̈ + N − Sτ − Σ Jᵀw‖∞ / max(1, ‖N‖∞), where every contact's wrench w
/// (reported on its surface entity) acts with the opposite sign on the other entity at the same
/// world point. Call after solve(), before integrate().
double eomResidual(const problem::MultiRobotProblem& p);

/// Largest violation of the Coulomb cone (|f_t| − μ f_n, and −f_n) over every point of every
/// active contact, the point forces being rebuilt from λ.
double coneViolation(const problem::MultiRobotProblem& p);

}  // namespace mrqp::testing
