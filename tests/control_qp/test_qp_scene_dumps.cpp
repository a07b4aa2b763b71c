// The QPs of controller scenes dumped by bench_controller --dump-qp into tests/data/qp/scenes
// (docs/BENCHMARKS.md, "Controller cycle"): every one must be solved Optimal, cold and warm, and
// the KKT conditions are checked here from the file data (H, g, A, b, C, l, u, xl, xu) and the
// returned x and multipliers, independently of the solver's own check. Sign convention
// (qp_solver.hpp): Hx + g + Aᵀy + Cᵀλ + μ = 0, λᵢ ≤ 0 at a lower side, ≥ 0 at an upper side.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "qp/qp_io.hpp"
#include "qp/qp_solver.hpp"

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;
using mrqp::qp::QpText;

namespace {

const std::string kDir = std::string(MRQP_TEST_DATA_DIR) + "/qp/scenes";

std::vector<std::string> dumpFiles() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(kDir, ec))
    if (e.is_regular_file() && e.path().extension() == ".qp") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

double infNorm(const Eigen::VectorXd& v) { return v.size() ? v.lpNorm<Eigen::Infinity>() : 0.0; }

struct Residuals {
  double primal = 0.0;  // largest violation, relative to max(1, |bound|)
  double dual = 0.0;    // ‖Hx + g + Aᵀy + Cᵀλ + μ‖∞, relative to the largest of its terms
  double sign = 0.0;    // wrong-sign multiplier, or one on an infinite side, relative
  double complementarity = 0.0;  // |multiplier| · distance to its side, relative
};

/// One side of a two-sided constraint lo ≤ value ≤ up with multiplier m (≤ 0 at lo, ≥ 0 at up).
void side(double value, double lo, double up, double m, double mscale, Residuals& r) {
  const double scale =
      std::max({1.0, std::isfinite(lo) ? std::abs(lo) : 0.0, std::isfinite(up) ? std::abs(up) : 0.0});
  r.primal = std::max(r.primal, std::max({0.0, lo - value, value - up}) / scale);
  if (lo == up) return;  // an equality: its multiplier has no sign
  if (m < 0.0) {
    if (!std::isfinite(lo))
      r.sign = std::max(r.sign, -m / mscale);
    else
      r.complementarity = std::max(r.complementarity, -m * std::abs(value - lo) / mscale / scale);
  } else if (m > 0.0) {
    if (!std::isfinite(up))
      r.sign = std::max(r.sign, m / mscale);
    else
      r.complementarity = std::max(r.complementarity, m * std::abs(up - value) / mscale / scale);
  }
}

Residuals kkt(const QpText& qp, const QpSolver& s) {
  const Eigen::VectorXd x = s.x(), y = s.equalityMultipliers(), lam = s.inequalityMultipliers(),
                        mu = s.boundMultipliers();
  Residuals r;
  const Eigen::VectorXd hx = qp.H * x;
  const Eigen::VectorXd aty = qp.me ? Eigen::VectorXd(qp.A.transpose() * y) : Eigen::VectorXd::Zero(qp.n);
  const Eigen::VectorXd ctl = qp.mi ? Eigen::VectorXd(qp.C.transpose() * lam) : Eigen::VectorXd::Zero(qp.n);
  const Eigen::VectorXd stationarity = hx + qp.g + aty + ctl + mu;
  r.dual = infNorm(stationarity) /
           std::max({1.0, infNorm(hx), infNorm(qp.g), infNorm(aty), infNorm(ctl), infNorm(mu)});
  const double mscale = std::max({1.0, infNorm(y), infNorm(lam), infNorm(mu)});
  if (qp.me) {
    const Eigen::VectorXd ax = qp.A * x;
    for (int i = 0; i < qp.me; ++i) side(ax(i), qp.b(i), qp.b(i), 0.0, mscale, r);
  }
  if (qp.mi) {
    const Eigen::VectorXd cx = qp.C * x;
    for (int i = 0; i < qp.mi; ++i) side(cx(i), qp.l(i), qp.u(i), lam(i), mscale, r);
  }
  for (int j = 0; j < qp.n; ++j) side(x(j), qp.xl(j), qp.xu(j), mu(j), mscale, r);
  return r;
}

void checkKkt(const QpText& qp, const QpSolver& s) {
  const Residuals r = kkt(qp, s);
  INFO("primal " << r.primal << ", dual " << r.dual << ", sign " << r.sign << ", complementarity "
                 << r.complementarity);
  CHECK(r.primal <= 1e-6);
  CHECK(r.dual <= 1e-6);
  CHECK(r.sign <= 1e-6);
  CHECK(r.complementarity <= 1e-6);
}

}  // namespace

TEST_CASE("qp: controller scene dumps are solved, KKT checked from the data", "[qp][scenes]") {
  const auto files = dumpFiles();
  INFO("directory " << kDir);
  REQUIRE(!files.empty());
  for (const auto& file : files) {
    INFO(file);
    QpText qp;
    std::string error;
    REQUIRE(mrqp::qp::readQpFile(file, qp, error));
    REQUIRE(qp.n > 0);
    QpProblem problem(qp.n, qp.me, qp.mi);
    REQUIRE(mrqp::qp::toProblem(qp, problem));

    QpSolver solver(problem);
    REQUIRE(solver.solve(problem) == QpStatus::Optimal);
    CHECK_FALSE(solver.info().warm_started);
    checkKkt(qp, solver);
    const Eigen::VectorXd x_cold = solver.x();
    const double f_cold = mrqp::qp::evaluateObjective(qp, x_cold);

    // The same QP again, warm started from its own optimal active set: no step, same answer.
    REQUIRE(solver.solve(problem) == QpStatus::Optimal);
    CHECK(solver.info().warm_started);
    CHECK_FALSE(solver.info().cold_restarted);
    CHECK(solver.info().iterations == 0);
    checkKkt(qp, solver);
    CHECK((solver.x() - x_cold).lpNorm<Eigen::Infinity>() <=
          1e-8 * std::max(1.0, x_cold.lpNorm<Eigen::Infinity>()));
    CHECK(std::abs(mrqp::qp::evaluateObjective(qp, solver.x()) - f_cold) <=
          1e-9 * std::max(1.0, std::abs(f_cold)));
  }
}
