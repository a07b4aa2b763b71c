#include "qp/qp_problem.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "qp/qp_status.hpp"

namespace mrqp::qp {

namespace {
int checkedCapacity(int value, const char* what) {
  if (value < 0) throw std::invalid_argument(std::string("QpProblem: negative ") + what);
  return value;
}
}  // namespace

QpProblem::QpProblem(int max_variables, int max_equalities, int max_inequalities)
    : max_n_(checkedCapacity(max_variables, "variable capacity")),
      max_me_(checkedCapacity(max_equalities, "equality capacity")),
      max_mi_(checkedCapacity(max_inequalities, "inequality capacity")),
      n_(max_n_),
      me_(max_me_),
      mi_(max_mi_),
      H_(max_n_, max_n_),
      A_(max_me_, max_n_),
      C_(max_mi_, max_n_),
      g_(max_n_),
      b_(max_me_),
      l_(max_mi_),
      u_(max_mi_),
      xl_(max_n_),
      xu_(max_n_) {
  clear();
}

bool QpProblem::resize(int n, int me, int mi) noexcept {
  if (n < 0 || me < 0 || mi < 0 || n > max_n_ || me > max_me_ || mi > max_mi_) return false;
  n_ = n;
  me_ = me;
  mi_ = mi;
  return true;
}

void QpProblem::clear() noexcept {
  constexpr double inf = std::numeric_limits<double>::infinity();
  H_.setZero();
  A_.setZero();
  C_.setZero();
  g_.setZero();
  b_.setZero();
  l_.setConstant(-inf);
  u_.setConstant(inf);
  xl_.setConstant(-inf);
  xu_.setConstant(inf);
}

double QpProblem::objective(const ConstVectorRef& x) const noexcept {
  double f = 0.0;
  for (int j = 0; j < n_; ++j) f += x(j) * (0.5 * H_.col(j).head(n_).dot(x) + g_(j));
  return f;
}

const char* toString(QpStatus status) noexcept {
  switch (status) {
    case QpStatus::Optimal:
      return "optimal";
    case QpStatus::Infeasible:
      return "infeasible";
    case QpStatus::IterationLimit:
      return "iteration-limit";
    case QpStatus::NumericalFailure:
      return "numerical-failure";
    case QpStatus::InvalidInput:
      return "invalid-input";
    case QpStatus::NotSolved:
      return "not-solved";
  }
  return "unknown";
}

const char* toString(QpInputError error) noexcept {
  switch (error) {
    case QpInputError::None:
      return "none";
    case QpInputError::CapacityExceeded:
      return "capacity-exceeded";
    case QpInputError::NonFiniteData:
      return "non-finite-data";
    case QpInputError::InvalidBounds:
      return "invalid-bounds";
    case QpInputError::NotConvex:
      return "not-convex";
  }
  return "unknown";
}

}  // namespace mrqp::qp
