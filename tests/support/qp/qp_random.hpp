// Random dense QPs with a known feasible point, for the tests and bench_qp (host-side helper:
// allocates; not for the control cycle).
#pragma once

#include <cstdint>
#include <random>

#include "qp/qp_problem.hpp"

namespace mrqp::qp {

struct RandomQpSpec {
  int n = 10;                    ///< variables
  int me = 0;                    ///< rows of A (independent with probability 1)
  int mi = 0;                    ///< rows of C
  bool bounds = true;            ///< finite variable bounds (otherwise ±inf)
  int hessian_rank = -1;         ///< rank of H; -1 = full rank (strictly convex)
  double hessian_shift = 1e-1;   ///< δ in H = MᵀM/n + δI (full rank only)
  double gradient_scale = 10.0;  ///< ‖g‖ relative to ‖H‖: large values make many constraints active
  double one_sided = 0.25;       ///< probability that a row has only a lower (or only an upper) side
};

/// Fills `problem` (resized to the spec, which must fit its capacity) with
///   H = MᵀM/n + δI (or a rank-deficient MᵀM), A, C Gaussian; a point x0 ∈ [-1, 1]ⁿ with
///   b = A x0, l < C x0 < u and xl < x0 < xu, so the problem is feasible.
/// Returns false if the spec does not fit the capacity.
bool generateRandomQp(const RandomQpSpec& spec, std::mt19937_64& rng, QpProblem& problem);

/// Perturbs g (relative to ‖g‖∞), the diagonal of H (relative, upwards) and every finite l, u,
/// xl, xu (absolute) by about `eps`; A, b and C are kept. For eps ≪ 0.1 the feasible point of
/// generateRandomQp stays feasible: the next QP of a control loop.
void perturbQp(double eps, std::mt19937_64& rng, QpProblem& problem);

}  // namespace mrqp::qp
