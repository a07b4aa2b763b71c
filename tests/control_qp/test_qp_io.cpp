// The QP text format: exact round trip of problems (dumps), reading the Maros–Meszaros files,
// and clear errors on malformed input.
#include <catch2/catch.hpp>

#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "qp/qp_io.hpp"
#include "qp/qp_random.hpp"

using mrqp::qp::QpProblem;
using mrqp::qp::QpText;

namespace {

bool sameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (!(a(i, j) == b(i, j)) || std::signbit(a(i, j)) != std::signbit(b(i, j))) return false;
  return true;
}

void checkSame(const QpText& a, const QpText& b) {
  CHECK(a.name == b.name);
  CHECK(a.n == b.n);
  CHECK(a.me == b.me);
  CHECK(a.mi == b.mi);
  CHECK(sameBits(a.H, b.H));
  CHECK(sameBits(a.g, b.g));
  CHECK(sameBits(a.A, b.A));
  CHECK(sameBits(a.b, b.b));
  CHECK(sameBits(a.C, b.C));
  CHECK(sameBits(a.l, b.l));
  CHECK(sameBits(a.u, b.u));
  CHECK(sameBits(a.xl, b.xl));
  CHECK(sameBits(a.xu, b.xu));
  CHECK(a.r == b.r);
  CHECK(a.has_objective == b.has_objective);
  CHECK(a.posdef == b.posdef);
}

std::string readError(const std::string& text) {
  std::istringstream in(text);
  QpText qp;
  std::string error;
  if (mrqp::qp::readQpText(in, qp, error)) return "";
  return error;
}

const char* kSmall =
    "# a comment\n"
    "name SMALL\n"
    "n 2 m 1 me 1\n"
    "P 2\n0 0 2\n0 1 1\n"
    "q 1 -1\n"
    "r 0.5\n"
    "A 1\n0 0 1\n"
    "b 3\n"
    "C 2\n0 0 1\n0 1 1\n"
    "l -inf\n"
    "u 4\n"
    "lb 0 -inf\n"
    "ub inf 7\n";

}  // namespace

TEST_CASE("qp: a dumped problem reads back bit for bit", "[qp][io]") {
  std::mt19937_64 rng(31);
  mrqp::qp::RandomQpSpec spec;
  spec.n = 17;
  spec.me = 4;
  spec.mi = 9;
  QpProblem p(20, 5, 10);
  REQUIRE(mrqp::qp::generateRandomQp(spec, rng, p));
  p.xl()(3) = -std::numeric_limits<double>::infinity();
  p.C()(2, 5) = 0.0;  // sparsity is kept
  p.g()(1) = 1e-300;
  p.g()(2) = -0.1;
  const QpText a = mrqp::qp::fromProblem(p, "scene_step_42");
  std::ostringstream out;
  REQUIRE(mrqp::qp::writeQpText(out, a));
  std::istringstream in(out.str());
  QpText b;
  std::string error;
  REQUIRE(mrqp::qp::readQpText(in, b, error));
  checkSame(a, b);
  // and into a problem of larger capacity, through a file
  const std::string path = "qp_io_roundtrip_test.qp";
  REQUIRE(mrqp::qp::dumpProblem(path, p, "scene step 42", error));
  QpText c;
  REQUIRE(mrqp::qp::readQpFile(path, c, error));
  std::remove(path.c_str());
  CHECK(c.name == "scene_step_42");
  QpProblem q(30, 10, 10);
  REQUIRE(mrqp::qp::toProblem(c, q));
  CHECK(q.n() == p.n());
  CHECK(sameBits(q.C(), p.C()));
  CHECK(sameBits(q.H(), p.H()));
  QpProblem tiny(3, 0, 0);
  CHECK_FALSE(mrqp::qp::toProblem(c, tiny));
}

TEST_CASE("qp: the format reads the Maros–Meszaros files and writes them back identically", "[qp][io]") {
  QpText a;
  std::string error;
  REQUIRE(mrqp::qp::readQpFile(std::string(MRQP_TEST_DATA_DIR) + "/qp/maros-meszaros/QPCBLEND.qp", a, error));
  CHECK(a.name == "QPCBLEND");
  CHECK(a.n == 83);
  CHECK(a.mi == 74);
  CHECK(a.me == 0);
  CHECK(a.posdef == 1);
  CHECK(a.has_objective);
  CHECK(a.H.isApprox(a.H.transpose()));
  std::ostringstream out;
  REQUIRE(mrqp::qp::writeQpText(out, a));
  std::istringstream in(out.str());
  QpText b;
  REQUIRE(mrqp::qp::readQpText(in, b, error));
  checkSame(a, b);
  CHECK(a.objective == b.objective);
}

TEST_CASE("qp: a small file with every section", "[qp][io]") {
  std::istringstream in(kSmall);
  QpText qp;
  std::string error;
  REQUIRE(mrqp::qp::readQpText(in, qp, error));
  CHECK(qp.H(1, 0) == 1.0);
  CHECK(qp.H(0, 1) == 1.0);
  CHECK(qp.me == 1);
  CHECK(qp.A(0, 0) == 1.0);
  CHECK(qp.b(0) == 3.0);
  CHECK(qp.l(0) == -std::numeric_limits<double>::infinity());
  CHECK(qp.xu(1) == 7.0);
  CHECK(qp.r == 0.5);
  CHECK_FALSE(qp.has_objective);
  const Eigen::Vector2d x(1.0, 2.0);
  CHECK(mrqp::qp::evaluateObjective(qp, x) == Approx(0.5 * (2 + 2 * 2 * 1) + 1 - 2 + 0.5));
}

TEST_CASE("qp: malformed QP files give an error with the line number", "[qp][io]") {
  const std::string good = kSmall;
  CHECK(readError(good).empty());
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto pos = s.find(from);
    REQUIRE(pos != std::string::npos);
    s.replace(pos, from.size(), to);
    return readError(s);
  };
  CHECK(replaced("q 1 -1\n", "q 1\n").find("line 7: 'q' needs 2 values") != std::string::npos);
  CHECK(replaced("0 1 1\n", "1 0 1\n").find("upper triangle") != std::string::npos);
  CHECK(replaced("C 2\n0 0 1\n0 1 1\n", "C 2\n0 1 1\n0 0 1\n").find("sorted") != std::string::npos);
  CHECK(replaced("b 3\n", "b x3\n").find("bad number 'x3'") != std::string::npos);
  CHECK(replaced("lb 0 -inf\n", "").find("expected 'lb'") != std::string::npos);
  CHECK(replaced("C 2\n0 0 1\n", "C 2\n5 0 1\n").find("out of range") != std::string::npos);
  CHECK(replaced("ub inf 7\n", "ub inf 7\nextra 1\n").find("unexpected 'extra'") != std::string::npos);
  CHECK(readError(good.substr(0, good.size() / 2)).find("line") != std::string::npos);
  CHECK(readError("").find("end of file") != std::string::npos);
  QpText qp;
  std::string error;
  CHECK_FALSE(mrqp::qp::readQpFile("/nonexistent/x.qp", qp, error));
  CHECK(error.find("cannot open") != std::string::npos);
}
