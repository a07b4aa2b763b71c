// The structured path of the QP solver (docs/qp.md, "6. The structured path"): a warm solve of a
// block-diagonal QP answered from the previous active set must be the same optimum as the dense
// path's and a cold solve's, must pass a KKT check computed here from the problem data, and must
// give way to the dense path whenever it cannot answer (dense or semi-definite H, dependent rows,
// a changed active set, infeasible or invalid data).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "block_qp.hpp"
#include "qp/qp_io.hpp"
#include "qp/qp_solver.hpp"
#include "qp_test_util.hpp"

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;
using Outcome = mrqp::qp::StructuredPath::Outcome;

namespace {

double relDiff(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

/// Solves p with a solver that has just solved it (warm: the structured path is tried) and with a
/// cold solver; both must agree.
struct Trio {
  explicit Trio(const QpProblem& p) : warm(p), dense(p), cold(p) {
    dense.settings().structured_path = false;
    cold.settings().warm_start = false;
  }
  QpSolver warm, dense, cold;
};

}  // namespace

TEST_CASE("qp structured: a control loop on block-diagonal QPs gives the dense path's optimum",
          "[qp][structured]") {
  std::mt19937_64 rng(2024);
  long solves = 0, structured = 0, changed = 0, fallbacks = 0, optimal = 0;
  double worst_x = 0.0, worst_obj = 0.0, worst_kkt = 0.0;
  for (int problem = 0; problem < 4; ++problem) {
    qptest::BlockQpSpec spec;
    spec.nq = 24 + 8 * problem;
    spec.nl = 16 + 4 * problem;
    spec.me = 8 + 2 * problem;
    spec.mi = 6 + 2 * problem;
    QpProblem p(spec.nq + spec.nl, spec.me, spec.mi);
    const Eigen::VectorXd x0 = qptest::generateBlockQp(spec, rng, p);
    Trio t(p);
    for (int step = 0; step < 300; ++step) {
      if (step == 150) {
        // a new coupling between two 1×1 blocks (the partition kept so far no longer holds)
        auto alone = [&](int j) { return p.H().col(j).cwiseAbs().sum() == std::abs(p.H()(j, j)); };
        int j = 0;
        while (j + 2 < spec.nq && !(alone(j) && alone(j + 1))) ++j;
        REQUIRE((alone(j) && alone(j + 1)));
        const double c = 0.1 * std::sqrt(p.H()(j, j) * p.H()(j + 1, j + 1));
        p.H()(j, j + 1) = p.H()(j + 1, j) = c;
      }
      // small steps keep the active set; every 25th step moves it
      qptest::perturbBlockQp(step % 25 == 24 ? 0.3 : 1e-3, x0, rng, p);
      const QpStatus s_warm = t.warm.solve(p);
      const QpStatus s_dense = t.dense.solve(p);
      const QpStatus s_cold = t.cold.solve(p);
      ++solves;
      REQUIRE(s_warm == s_cold);
      REQUIRE(s_dense == s_cold);
      const auto& info = t.warm.info();
      if (info.structured) {
        ++structured;
        changed += info.iterations > 0;  // the guess was changed before it was optimal
        CHECK(info.iterations <= 12);
      } else if (info.structured_tried) {
        ++fallbacks;
      }
      if (s_cold != QpStatus::Optimal) continue;
      ++optimal;
      worst_x = std::max({worst_x, relDiff(t.warm.x(), t.cold.x()), relDiff(t.dense.x(), t.cold.x())});
      worst_obj = std::max(worst_obj, std::abs(t.warm.objective() - t.cold.objective()) /
                                          std::max(1.0, std::abs(t.cold.objective())));
      // as accurate as the cold solve (a problem of the loop may itself allow no better)
      worst_kkt = std::max(worst_kkt, qptest::kktErrors(p, t.warm).worst() /
                                          std::max(1e-9, qptest::kktErrors(p, t.cold).worst()));
    }
  }
  INFO("solves " << solves << ", answered by the structured path " << structured << " (" << changed
                 << " after changing the guess), fallbacks " << fallbacks);
  CHECK(optimal == solves);
  // the path is exercised both ways: it answers most solves and gives way when the set moves
  CHECK(structured > solves / 2);
  CHECK(changed > 0);
  CHECK(fallbacks > 0);
  CHECK(worst_x < 1e-8);
  CHECK(worst_obj < 1e-10);
  CHECK(worst_kkt <= 2.0);  // KKT error ≤ max(1e-9, 2 × the cold solve's)
}

TEST_CASE("qp structured: the controller's scene QPs", "[qp][structured]") {
  const std::string dir = std::string(MRQP_TEST_DATA_DIR) + "/qp/scenes";
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".qp") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  REQUIRE(!files.empty());
  int answered = 0;
  for (const auto& file : files) {
    mrqp::qp::QpText text;
    std::string error;
    REQUIRE(mrqp::qp::readQpFile(file, text, error));
    QpProblem p(text.n, text.me, text.mi);
    REQUIRE(mrqp::qp::toProblem(text, p));
    Trio t(p);
    REQUIRE(t.warm.solve(p) == QpStatus::Optimal);  // cold: nothing to warm start from
    REQUIRE(!t.warm.info().structured_tried);
    REQUIRE(t.cold.solve(p) == QpStatus::Optimal);
    // the same QP again, as a control cycle whose active set did not change
    REQUIRE(t.warm.solve(p) == QpStatus::Optimal);
    const auto& info = t.warm.info();
    INFO(file << ": outcome " << static_cast<int>(info.structured_outcome));
    REQUIRE(info.structured_tried);
    // the Panda alone has one dense 7×7 task block in an 8×8 H: not structured
    const bool panda_only = file.find("panda_reach") != std::string::npos;
    CHECK(info.structured == !panda_only);
    if (panda_only) CHECK(info.structured_outcome == Outcome::NotStructured);
    answered += info.structured;
    CHECK(relDiff(t.warm.x(), t.cold.x()) < 1e-9);
    CHECK(qptest::kktErrors(p, t.warm).worst() < 1e-9);
    CHECK(info.active_bounds == t.cold.info().active_bounds);
    CHECK(info.active_inequalities == t.cold.info().active_inequalities);
  }
  CHECK(answered >= 4);
}

TEST_CASE("qp structured: gives way to the dense path when it cannot answer", "[qp][structured]") {
  std::mt19937_64 rng(77);
  qptest::BlockQpSpec spec;
  QpProblem p(spec.nq + spec.nl, spec.me + 1, spec.mi);
  qptest::generateBlockQp(spec, rng, p);
  const QpProblem base = p;

  // solves base, then the modified p warm; returns the warm solver's outcome, checks the answer
  // (x only where it is unique: H positive definite)
  auto run = [&](QpStatus expected, bool unique = true) {
    Trio t(p);
    QpProblem first = base;
    first.resize(p.n(), p.me(), p.mi());
    REQUIRE(t.warm.solve(first) == QpStatus::Optimal);
    const QpStatus s = t.warm.solve(p);
    CHECK(s == expected);
    CHECK(t.cold.solve(p) == expected);
    CHECK(!t.warm.info().structured);
    if (s == QpStatus::Optimal) {
      CHECK(std::abs(t.warm.objective() - t.cold.objective()) <=
            1e-8 * std::max(1.0, std::abs(t.cold.objective())));
      if (unique) CHECK(relDiff(t.warm.x(), t.cold.x()) < 1e-8);
    }
    return t.warm.info().structured_outcome;
  };

  SECTION("a dense H") {
    for (int i = 0; i < p.n(); ++i)
      for (int j = 0; j < p.n(); ++j) p.H()(i, j) += i == j ? 1.0 : 1e-3;
    CHECK(run(QpStatus::Optimal) == Outcome::NotStructured);
  }
  SECTION("a semi-definite H") {
    p.H()(1, 1) = 0.0;
    p.H().row(1).setZero();
    p.H().col(1).setZero();
    CHECK(run(QpStatus::Optimal, false) == Outcome::NotDefinite);
  }
  SECTION("dependent equalities") {
    p.resize(p.n(), spec.me + 1, p.mi());
    p.A().row(spec.me) = 2.0 * p.A().row(0);
    p.b()(spec.me) = 2.0 * p.b()(0);
    CHECK(run(QpStatus::Optimal) == Outcome::Dependent);
  }
  SECTION("a changed active set") {
    p.g() = -p.g();
    CHECK(run(QpStatus::Optimal) == Outcome::WrongActiveSet);
  }
  SECTION("infeasible rows") {
    p.C().row(1) = p.C().row(2);
    p.l()(1) = 5.0;
    p.u()(1) = 6.0;
    p.l()(2) = -6.0;
    p.u()(2) = -5.0;
    run(QpStatus::Infeasible);
  }
  SECTION("NaN in a row and in a bound") {
    p.C()(p.mi() - 1, 0) = std::numeric_limits<double>::quiet_NaN();
    run(QpStatus::InvalidInput);
    p = base;
    p.xu()(spec.nq + 1) = std::numeric_limits<double>::quiet_NaN();
    run(QpStatus::InvalidInput);
  }
}

TEST_CASE("qp structured: switched off, the solver takes the dense path only", "[qp][structured]") {
  std::mt19937_64 rng(5);
  QpProblem p(60, 20, 20);
  qptest::generateBlockQp(qptest::BlockQpSpec(), rng, p);
  QpSolver s(p);
  s.settings().structured_path = false;
  REQUIRE(s.solve(p) == QpStatus::Optimal);
  REQUIRE(s.solve(p) == QpStatus::Optimal);
  CHECK(!s.info().structured_tried);
  CHECK(!s.info().structured);
  s.settings().structured_path = true;
  REQUIRE(s.solve(p) == QpStatus::Optimal);
  CHECK(s.info().structured);
}
