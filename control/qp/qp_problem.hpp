// Storage of a dense convex QP with a capacity fixed at construction (docs/qp.md):
//
//   minimize    ½ xᵀ H x + gᵀ x
//   subject to  A x  = b          (me rows)
//               l  ≤ C x ≤ u      (mi rows, either side may be ±inf; l == u is an equality)
//               xl ≤  x  ≤ xu     (n bounds, ±inf allowed; xl == xu fixes a variable)
//
// The active size (n, me, mi) may be anything up to the capacity and may change between solves:
// resize() never allocates and the accessors return views of the active top-left blocks.
// H need not be symmetric: the solver uses its symmetric part ½(H + Hᵀ), which defines the same
// objective. Only the constructor allocates.
#pragma once

#include <Eigen/Core>

namespace mrqp::qp {

class QpProblem {
 public:
  using MatrixRef = Eigen::Ref<Eigen::MatrixXd>;
  using ConstMatrixRef = Eigen::Ref<const Eigen::MatrixXd>;
  using VectorRef = Eigen::Ref<Eigen::VectorXd>;
  using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;

  /// Allocates storage for up to max_variables variables, max_equalities rows of A and
  /// max_inequalities rows of C (each ≥ 0), and sets the active size to the full capacity with
  /// clear()ed data.
  QpProblem(int max_variables, int max_equalities, int max_inequalities);

  int maxVariables() const noexcept { return max_n_; }
  int maxEqualities() const noexcept { return max_me_; }
  int maxInequalities() const noexcept { return max_mi_; }

  /// Sets the active size. Returns false (and changes nothing) if a size is negative or above the
  /// capacity. The data is not touched: entries that become active keep whatever was stored there
  /// before, so fill every active entry (or clear()) after a resize.
  bool resize(int n, int me, int mi) noexcept;

  /// Zeroes H, g, A, b, C over the whole capacity and makes every bound infinite
  /// (l = xl = -inf, u = xu = +inf).
  void clear() noexcept;

  int n() const noexcept { return n_; }
  int me() const noexcept { return me_; }
  int mi() const noexcept { return mi_; }

  // Views of the active blocks (n×n, n, me×n, me, mi×n, mi, mi, n, n).
  MatrixRef H() noexcept { return H_.topLeftCorner(n_, n_); }
  VectorRef g() noexcept { return g_.head(n_); }
  MatrixRef A() noexcept { return A_.topLeftCorner(me_, n_); }
  VectorRef b() noexcept { return b_.head(me_); }
  MatrixRef C() noexcept { return C_.topLeftCorner(mi_, n_); }
  VectorRef l() noexcept { return l_.head(mi_); }
  VectorRef u() noexcept { return u_.head(mi_); }
  VectorRef xl() noexcept { return xl_.head(n_); }
  VectorRef xu() noexcept { return xu_.head(n_); }

  ConstMatrixRef H() const noexcept { return H_.topLeftCorner(n_, n_); }
  ConstVectorRef g() const noexcept { return g_.head(n_); }
  ConstMatrixRef A() const noexcept { return A_.topLeftCorner(me_, n_); }
  ConstVectorRef b() const noexcept { return b_.head(me_); }
  ConstMatrixRef C() const noexcept { return C_.topLeftCorner(mi_, n_); }
  ConstVectorRef l() const noexcept { return l_.head(mi_); }
  ConstVectorRef u() const noexcept { return u_.head(mi_); }
  ConstVectorRef xl() const noexcept { return xl_.head(n_); }
  ConstVectorRef xu() const noexcept { return xu_.head(n_); }

  /// ½ xᵀHx + gᵀx for x of size n (the constant of a test-set file is not part of the problem).
  double objective(const ConstVectorRef& x) const noexcept;

 private:
  int max_n_, max_me_, max_mi_;
  int n_ = 0, me_ = 0, mi_ = 0;
  Eigen::MatrixXd H_, A_, C_;
  Eigen::VectorXd g_, b_, l_, u_, xl_, xu_;
};

}  // namespace mrqp::qp
