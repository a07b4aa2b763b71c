// The Maros–Meszaros subset of tests/data/qp/maros-meszaros (README there): every problem is
// solved; the objective f = ½xᵀPx + qᵀx + r from the returned x must match the reference to
// |f − f_ref| ≤ 1e-6·max(1, |f_ref|) on every positive-definite problem, and on the semi-definite
// ones the solver either matches or reports a non-optimal status — never a wrong "optimal".
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "qp/qp_io.hpp"
#include "qp/qp_solver.hpp"

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;
using mrqp::qp::QpText;

namespace {

const std::string kDir = std::string(MRQP_TEST_DATA_DIR) + "/qp/maros-meszaros";

double primalViolation(const QpText& qp, const Eigen::VectorXd& x) {
  const Eigen::VectorXd cx = qp.C * x;
  double v = 0.0;
  for (int i = 0; i < qp.mi; ++i)
    v = std::max({v, (qp.l(i) - cx(i)) / std::max(1.0, std::abs(qp.l(i))),
                  (cx(i) - qp.u(i)) / std::max(1.0, std::abs(qp.u(i)))});
  for (int j = 0; j < qp.n; ++j)
    v = std::max({v, (qp.xl(j) - x(j)) / std::max(1.0, std::abs(qp.xl(j))),
                  (x(j) - qp.xu(j)) / std::max(1.0, std::abs(qp.xu(j)))});
  return v;
}

}  // namespace

TEST_CASE("qp: Maros–Meszaros subset: reference objectives", "[qp][maros-meszaros]") {
  std::ifstream index(kDir + "/INDEX.tsv");
  REQUIRE(index);
  std::string line;
  std::getline(index, line);
  int problems = 0, matched_pd = 0, pd = 0, matched_psd = 0;
  while (std::getline(index, line)) {
    std::istringstream ss(line);
    std::string name;
    int n = 0, m = 0, meq = 0, posdef = 0;
    double objective = 0.0;
    ss >> name >> n >> m >> meq >> posdef >> objective;
    QpText qp;
    std::string error;
    INFO(name);
    REQUIRE(mrqp::qp::readQpFile(kDir + "/" + name + ".qp", qp, error));
    REQUIRE(qp.n == n);
    REQUIRE(qp.mi == m);
    REQUIRE(qp.posdef == posdef);
    QpProblem p(qp.n, qp.me, qp.mi);
    REQUIRE(mrqp::qp::toProblem(qp, p));
    QpSolver solver(p);
    const QpStatus st = solver.solve(p);
    const double f = mrqp::qp::evaluateObjective(qp, solver.x());
    const bool match = std::abs(f - qp.objective) <= 1e-6 * std::max(1.0, std::abs(qp.objective));
    INFO("status " << mrqp::qp::toString(st) << " f " << f << " reference " << qp.objective);
    if (posdef) {
      ++pd;
      REQUIRE(st == QpStatus::Optimal);
      CHECK(match);
      matched_pd += match;
    } else if (st == QpStatus::Optimal) {
      CHECK(match);  // never a wrong "optimal"
      matched_psd += match;
    }
    if (st == QpStatus::Optimal) {
      CHECK(primalViolation(qp, solver.x()) <= 1e-6);
      // solving again warm from its own active set gives the same answer without a step
      const Eigen::VectorXd x = solver.x();
      REQUIRE(solver.solve(p) == QpStatus::Optimal);
      CHECK(std::abs(mrqp::qp::evaluateObjective(qp, solver.x()) - f) <= 1e-6 * std::max(1.0, std::abs(f)));
      CHECK(solver.info().warm_started);
    }
    ++problems;
  }
  CHECK(problems == 44);
  CHECK(pd == 16);
  CHECK(matched_pd == 16);
  // a floor on the semi-definite ones, so that a regression to "non-optimal everywhere" shows
  CHECK(matched_psd >= 26);
}
