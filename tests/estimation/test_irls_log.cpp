// The batch estimate over a run's log (tools/irls): a log written here in mrqp-run's column layout
// from a known θ — rows of the regression on the cycles with an accepted update, NaN-free filler on
// the others — gives θ back exactly (1e-9) without noise; with noise the batch equals plain least
// squares of the same rows when Huber's threshold is out of reach, and adding the prior as rows
// equals the Gaussian posterior; a log without estimation columns or with a bad cell is an error
// naming file, line and column.
#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "irls_log.hpp"

using namespace mrqp;

namespace {

struct SyntheticLog {
  std::string path;
  Eigen::MatrixXd Y;  // the accepted rows, stacked
  Eigen::VectorXd mu;
};

/// A log with one entity "box" whose state is (m, hx, hy, hz), nv = 6, `cycles` rows, an update
/// accepted every third row, μ = Y θ + noise·N(0, 1).
SyntheticLog writeLog(const std::string& name, const Eigen::Vector4d& theta, double noise, int cycles,
                      const Eigen::Vector4d& prior, const Eigen::Vector4d& prior_std) {
  const char* names[4] = {"m", "hx", "hy", "hz"};
  SyntheticLog out;
  out.path = name;
  std::ofstream f(name);
  f << "t,other";
  for (const char* n : names) f << ",est_box_theta_" << n;
  for (const char* n : names) f << ",est_box_theta_std_" << n;
  f << ",est_box_accepted";
  for (int r = 0; r < 6; ++r) {
    for (const char* n : names) f << ",est_box_row" << r << "_" << n;
    f << ",est_box_row" << r << "_mu";
  }
  f << "\n";
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> ys, ms;
  f.precision(17);
  for (int k = 0; k < cycles; ++k) {
    const bool accepted = k % 3 == 1;
    f << 1e-3 * k << "," << 42;
    const Eigen::Vector4d th = k == 0 ? prior : theta + Eigen::Vector4d::Constant(0.01 * k);  // "online" column
    const Eigen::Vector4d sd = k == 0 ? prior_std : Eigen::Vector4d::Constant(0.5);
    for (int i = 0; i < 4; ++i) f << "," << th(i);
    for (int i = 0; i < 4; ++i) f << "," << sd(i);
    f << "," << (accepted ? 1 : 0);
    for (int r = 0; r < 6; ++r) {
      Eigen::Vector4d y;
      for (int i = 0; i < 4; ++i) y(i) = g(rng);
      const double m = y.dot(theta) + noise * g(rng);
      for (int i = 0; i < 4; ++i) f << "," << y(i);
      f << "," << m;
      if (accepted) {
        ys.insert(ys.end(), y.data(), y.data() + 4);
        ms.push_back(m);
      }
    }
    f << "\n";
  }
  const auto n = static_cast<Eigen::Index>(ms.size());
  out.Y = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>>(ys.data(), n, 4);
  out.mu = Eigen::Map<Eigen::VectorXd>(ms.data(), n);
  return out;
}

}  // namespace

TEST_CASE("mrqp-irls: a noise-free log gives the known θ to 1e-9", "[estimation][irls]") {
  const Eigen::Vector4d theta(0.941, 0.0376, 0.0565, -0.0188);
  const SyntheticLog log = writeLog("irls_exact.csv", theta, 0.0, 300, Eigen::Vector4d(0.1, 0, 0, 0),
                                    Eigen::Vector4d(1, 0.1, 0.1, 0.1));
  const std::vector<irls::EntityBatch> batches = irls::readBatches(log.path);
  REQUIRE(batches.size() == 1);
  const irls::EntityBatch& b = batches[0];
  CHECK(b.entity == "box");
  CHECK(b.names == std::vector<std::string>{"m", "hx", "hy", "hz"});
  CHECK(b.updates == 100);
  CHECK(b.Y.rows() == 600);
  CHECK((b.Y - log.Y).cwiseAbs().maxCoeff() < 1e-14);
  CHECK(b.prior(0) == 0.1);
  CHECK(b.online(0) == Approx(theta(0) + 0.01 * 299));
  const irls::BatchResult r = irls::estimate(b, false, {});
  CHECK(r.irls.rank == 4);
  CHECK((r.irls.theta - theta).cwiseAbs().maxCoeff() < 1e-9);
  const std::string json = irls::toJson({r}, false, 1.345);
  CHECK(json.find("\"box\"") != std::string::npos);
  CHECK(json.find("\"parameters\": [\"m\", \"hx\", \"hy\", \"hz\"]") != std::string::npos);
  CHECK(irls::toText({r}).find("hz") != std::string::npos);
  std::remove(log.path.c_str());
}

TEST_CASE("mrqp-irls: with noise, least squares and the Gaussian posterior of the same rows",
          "[estimation][irls]") {
  const Eigen::Vector4d theta(0.941, 0.0376, 0.0565, -0.0188);
  const Eigen::Vector4d prior(0.1, 0, 0, 0), prior_std(1, 0.1, 0.1, 0.1);
  const SyntheticLog log = writeLog("irls_noise.csv", theta, 1.0, 600, prior, prior_std);
  const irls::EntityBatch b = irls::readBatches(log.path).at(0);
  estimation::IrlsOptions far;
  far.huber_k = 1e9;  // every row weighted 1: plain least squares
  const irls::BatchResult r = irls::estimate(b, false, far);
  const Eigen::Vector4d ls = log.Y.colPivHouseholderQr().solve(log.mu);
  CHECK((r.irls.theta - ls).cwiseAbs().maxCoeff() < 1e-12);
  const Eigen::Matrix4d cov = (log.Y.transpose() * log.Y).inverse();
  CHECK((r.irls.covariance - cov).cwiseAbs().maxCoeff() < 1e-12);
  // Within 4σ of the truth (unit noise, the reported covariance).
  for (int i = 0; i < 4; ++i) CHECK(std::abs(r.irls.theta(i) - theta(i)) < 4.0 * std::sqrt(cov(i, i)));
  // With the prior as rows: the posterior mean (P0⁻¹ + YᵀY)⁻¹ (P0⁻¹ θ0 + Yᵀ μ).
  const Eigen::Matrix4d P0inv = prior_std.cwiseAbs2().cwiseInverse().asDiagonal();
  const Eigen::Matrix4d info = P0inv + log.Y.transpose() * log.Y;
  const Eigen::Vector4d post = info.ldlt().solve(P0inv * prior + log.Y.transpose() * log.mu);
  const irls::BatchResult rp = irls::estimate(b, true, far);
  CHECK((rp.irls.theta - post).cwiseAbs().maxCoeff() < 1e-12);
  // Huber's default: close to least squares on Gaussian noise (≈5 % of the rows beyond 1.345σ).
  const irls::BatchResult rh = irls::estimate(b, false, {});
  CHECK(rh.irls.outlier_fraction > 0.05);
  CHECK(rh.irls.outlier_fraction < 0.4);
  // Huber and least squares differ by about 0.23 σ per parameter here (the efficiency 0.95).
  for (int i = 0; i < 4; ++i) CHECK(std::abs(rh.irls.theta(i) - ls(i)) < std::sqrt(cov(i, i)));
  std::remove(log.path.c_str());
}

TEST_CASE("mrqp-irls: bad logs are errors naming file, line and column", "[estimation][irls]") {
  {
    std::ofstream f("irls_none.csv");
    f << "t,a\n0,1\n";
  }
  CHECK_THROWS_WITH(irls::readBatches("irls_none.csv"), Catch::Contains("irls_none.csv:1: no estimation columns"));
  const SyntheticLog log = writeLog("irls_bad.csv", Eigen::Vector4d(1, 0, 0, 0), 0.0, 5, Eigen::Vector4d(1, 0, 0, 0),
                                    Eigen::Vector4d::Ones());
  {
    std::ifstream in(log.path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;  // the third line (k = 1, accepted)
    const std::size_t cell = text.find(",1,", line3);
    text.replace(cell + 1, 1, "x");
    std::ofstream out(log.path);
    out << text;
  }
  CHECK_THROWS_WITH(irls::readBatches(log.path),
                    Catch::Contains("irls_bad.csv:3: est_box_accepted: not a number: 'x'"));
  CHECK_THROWS_WITH(irls::readBatches("no_such_dir/log.csv"), Catch::Contains("no_such_dir/log.csv: cannot read"));
  std::remove(log.path.c_str());
  std::remove("irls_none.csv");
}
