// The structured path of QpSolver (docs/qp.md, "6. The structured path"): the warm solve of a QP
// whose Hessian is block-diagonal, for the active set of the previous solve taken as a guess.
//
// The multi-robot problem's Hessian is one small block per entity or task, most of them 1×1
// (posture, force minimisation, regularisation), and from one control cycle to the next its
// active set rarely changes (the same friction-cone generators λ ≥ 0 at zero). For that guess:
//   - the variables at an active or fixed bound (set B) are removed as columns: x_B is known;
//   - the remaining equality-constrained QP over the free variables F,
//         min ½ x_Fᵀ H_FF x_F + (g_F + H_FB x_B)ᵀ x_F   s.t.  E_F x_F = e − E_B x_B,
//     E = [A; rows of C with l = u; rows of C active on a side], is solved by the range-space
//     method: H_FF = L Lᵀ block by block, W = L⁻¹E_Fᵀ, S = WᵀW = E_F H_FF⁻¹ E_Fᵀ = UᵀU,
//         S ν = −(e − E_B x_B) − Wᵀ L⁻¹ g̃,   x_F = −L⁻ᵀ(L⁻¹ g̃ + W ν),
//     with one step of iterative refinement on the KKT residual when the first answer is not
//     accurate enough;
//   - the bound multipliers are μ_B = −(Hx + g + Aᵀy + Cᵀλ)_B.
// The answer is accepted only if it is the optimum: every active multiplier has its sign (within
// the dual tolerance), no inactive constraint is violated (within the primal tolerance), and the
// solver's KKT check on the original data holds (kkt_tolerance). The KKT conditions are sufficient
// because the full H is proved positive definite (its block Cholesky). Otherwise the solver falls
// back to its dense path. The block partition of H is kept from one solve to the next and only
// verified (every entry outside the blocks zero) while it holds. Allocation-free after construction.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "qp/qp_problem.hpp"

namespace mrqp::qp {

struct QpSettings;
struct QpInfo;

class StructuredPath {
 public:
  enum class Outcome : std::uint8_t {
    Solved,          ///< the guessed active set is optimal: x and the multipliers are the answer
    NotStructured,   ///< H is not block-diagonal with small enough blocks (dense path)
    NotDefinite,     ///< a block of H is not safely positive definite (dense path: proximal)
    Dependent,       ///< the equality and active rows are (nearly) dependent on the free variables
    WrongActiveSet,  ///< a multiplier of the wrong sign or a violated inactive constraint
    Inaccurate,      ///< the KKT check failed even after refinement
  };

  /// Allocates everything for problems up to this size.
  StructuredPath(int max_variables, int max_equalities, int max_inequalities);

  /// Solves `p` starting from the active set given by row_side (mi entries) and bound_side (n
  /// entries): +1 lower side active, −1 upper side active, 0 inactive; only finite sides of
  /// inequalities may be marked. Rows with l = u and variables with xl = xu are equalities
  /// whatever is marked. When the answer for a guess is not optimal, the next guess makes the
  /// violated constraints active and releases those with a wrong-sign multiplier (at most three
  /// changes of the guess). On Solved, row_side and bound_side hold the optimal active set, x, y,
  /// lambda, mu (sized n, me, mi, n) the answer and info its residuals, rank, objective and the
  /// number of constraints added or released (iterations); on any other outcome they hold nothing
  /// useful. `p` must have passed the solver's validation (finite data, consistent bounds).
  /// noexcept, allocation-free.
  Outcome solve(const QpProblem& p, const QpSettings& settings, std::int8_t* row_side,
                std::int8_t* bound_side, Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> y,
                Eigen::Ref<Eigen::VectorXd> lambda, Eigen::Ref<Eigen::VectorXd> mu, QpInfo& info) noexcept;

  /// Blocks of the last partition of H (0 before the first solve) and the largest block's size.
  int blockCount() const noexcept { return nb_; }
  int largestBlock() const noexcept { return largest_; }
  /// Whether the last solve found H structured (Σ block size³ ≤ n³/4).
  bool structured() const noexcept { return structured_; }
  /// Refinement steps taken by the last solve (all guesses together).
  int refinements() const noexcept { return refinements_; }
  /// Constraints added or released between guesses in the last solve.
  int changes() const noexcept { return changes_; }

 private:
  Outcome solveGuess(const QpProblem& p, const QpSettings& settings, double threshold, std::int8_t* row_side,
                     std::int8_t* bound_side, Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> y,
                     Eigen::Ref<Eigen::VectorXd> lambda, Eigen::Ref<Eigen::VectorXd> mu, QpInfo& info,
                     int& changes) noexcept;
  bool blocksHold(const QpProblem::ConstMatrixRef& H) const noexcept;
  void detectBlocks(const QpProblem::ConstMatrixRef& H) noexcept;
  bool factorFullBlocks(const QpProblem::ConstMatrixRef& H, double threshold) noexcept;
  bool factorFreeBlocks(const QpProblem::ConstMatrixRef& H, double threshold) noexcept;
  void solveL(Eigen::Ref<Eigen::VectorXd> v, int first, int& last) const noexcept;  // v ← L⁻¹v
  void solveLt(Eigen::Ref<Eigen::VectorXd> v) const noexcept;                       // v ← L⁻ᵀv
  void hessianTimes(const QpProblem::ConstMatrixRef& H, const Eigen::Ref<const Eigen::VectorXd>& v,
                    Eigen::Ref<Eigen::VectorXd> out) const noexcept;  // out = ½(H + Hᵀ) v
  void solveKkt(Eigen::Ref<Eigen::VectorXd> rf, const Eigen::Ref<const Eigen::VectorXd>& re,
                Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> nu) const noexcept;

  int max_n_, max_me_, max_mi_, max_e_;
  // block partition of H: block k holds variables block_start_[k] .. block_start_[k+1]−1;
  // multi_ lists the blocks of size > 1
  int part_n_ = -1, nb_ = 0, nmulti_ = 0, largest_ = 0;
  bool structured_ = false;
  int refinements_ = 0, changes_ = 0;
  std::vector<std::int32_t> block_start_, lo_, hi_, multi_;
  // factor of H (standard L inside the blocks of size > 1; proves convexity) and of H_FF as
  // L = L̃ D (unit lower L̃ inside its blocks of size > 1 at fmulti_ with fmulti_size_, 1/D in dinv_)
  Eigen::MatrixXd Lh_, Lf_;
  Eigen::VectorXd dinv_;
  int nfmulti_ = 0;
  std::vector<std::int32_t> fmulti_, fmulti_size_;
  // free variables (F index → variable), variable → F index or −1, the bound-fixed variables
  int nf_ = 0;
  std::vector<std::int32_t> free_, pos_, bound_list_;
  // equality rows E (the first me are the rows of A, then rows of C), their ranges in F space
  int ne_ = 0;
  std::vector<std::int32_t> esrc_, first_, last_;
  Eigen::MatrixXd W_, S_;  // W = L⁻¹E_Fᵀ (nf × ne), S = WᵀW = UᵀU (U in the upper triangle)
  Eigen::VectorXd xb_, e_, nu_, dnu_, re_, xf_, dxf_, rf_, hx_, aty_, ctl_, res_, cx_, ax_;
};

}  // namespace mrqp::qp
