// Outcome of a QP solve (docs/qp.md). Every failure is reported by value: the solver never
// throws, and a status other than Optimal means the returned point must not be used as a solution.
#pragma once

#include <cstdint>

namespace mrqp::qp {

enum class QpStatus : std::uint8_t {
  Optimal,           ///< KKT conditions hold to the tolerances (and were checked after the solve)
  Infeasible,        ///< the constraints have no common point (a dual certificate was found)
  IterationLimit,    ///< the active-set or proximal iteration budget ran out
  NumericalFailure,  ///< breakdown or a final KKT check that failed: the answer is not trusted
  InvalidInput,      ///< see QpInputError: NaN/inf data, l > u, capacity exceeded, non-convex H
  NotSolved,         ///< no solve has been run yet
};

/// Why a solve returned QpStatus::InvalidInput.
enum class QpInputError : std::uint8_t {
  None,
  CapacityExceeded,  ///< the problem is larger than the solver was built for
  NonFiniteData,     ///< NaN or ±inf in H, g, A, b or C; NaN in a bound
  InvalidBounds,     ///< l > u or xl > xu, or a lower bound of +inf, or an upper bound of -inf
  NotConvex,         ///< H is not positive semi-definite on the null space of the equalities
};

/// Names for logs and tables ("optimal", "infeasible", ...). Static strings; never null.
const char* toString(QpStatus status) noexcept;
const char* toString(QpInputError error) noexcept;

}  // namespace mrqp::qp
