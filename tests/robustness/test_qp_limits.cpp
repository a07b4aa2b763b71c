// The QP text reader against hostile files (tests/support/qp/qp_io.hpp, docs/robustness.md):
// sizes the file cannot hold are refused before anything is allocated from them, the dense
// matrices stay within their limit, non-finite numbers are refused where they are read, and an
// endless input is cut at the size limit. The allocation bound is proven in a child process whose
// address space is limited (bounded_child.hpp): a reader that allocated n×n doubles first would
// run out of memory there instead of answering.
#include <catch2/catch.hpp>

#include <cstdio>
#include <sstream>
#include <string>

#include "bounded_child.hpp"
#include "qp/qp_io.hpp"

using mrqp::qp::QpText;
using mrqp::testing::ChildEnd;
using mrqp::testing::runBounded;

namespace {

std::string readError(const std::string& text) {
  std::istringstream in(text);
  QpText qp;
  std::string error;
  return mrqp::qp::readQpText(in, qp, error) ? std::string() : error;
}

std::string values(int count, const char* value) {
  std::string s;
  for (int i = 0; i < count; ++i) {
    s += ' ';
    s += value;
  }
  return s;
}

// A valid QP of n variables, no rows, H = I (written as P triplets).
std::string identityQp(int n) {
  std::string s = "name big\nn " + std::to_string(n) + " m 0\nP " + std::to_string(n) + "\n";
  for (int i = 0; i < n; ++i) s += std::to_string(i) + " " + std::to_string(i) + " 1\n";
  s += "q" + values(n, "0") + "\nr 0\nC 0\nl\nu\nlb" + values(n, "-inf") + "\nub" + values(n, "inf") + "\n";
  return s;
}

}  // namespace

TEST_CASE("qp text: a 27-byte file declaring n = 100000000 is refused before any allocation",
          "[robustness][qp]") {
  const std::string text = "name a\nn 100000000 m 0\nP 0\n";
  REQUIRE(text.size() == 27);
  std::string error;
  const ChildEnd end = runBounded([&] {
    error = readError(text);
    return !error.empty();
  });
  CHECK(end == ChildEnd::ReturnedTrue);
  error = readError(text);
  CHECK(error.find("line 2: ") == 0);
  CHECK(error.find("need at least 600000000 bytes of values; the file holds 27") != std::string::npos);
}

TEST_CASE(
    "qp text: n = 15000 in a small file is refused, and with its values read it is still over the dense "
    "limit",
    "[robustness][qp]") {
  const std::string small = "name a\nn 15000 m 0\nP 0\nq 0\nr 0\nC 0\nl\nu\nlb 0\nub 0\n";
  CHECK(runBounded([&] { return !readError(small).empty(); }) == ChildEnd::ReturnedTrue);
  CHECK(readError(small).find("line 2: n 15000, m 0, me 0 need at least 90000 bytes") == 0);

  // The same n with every value present: the lines are read (a few hundred kilobytes), then the
  // 15000 × 15000 matrix (1.8 GB) is refused by the dense limit, naming the header's line.
  const std::string full = "name a\nn 15000 m 0\nP 0\nq" + values(15000, "0") + "\nr 0\nC 0\nl\nu\nlb" +
                           values(15000, "0") + "\nub" + values(15000, "1") + "\n";
  std::string error;
  CHECK(runBounded([&] { return !readError(full).empty(); }) == ChildEnd::ReturnedTrue);
  error = readError(full);
  CHECK(error ==
        "line 2: n x (n + me + m) = 225000000 matrix entries, more than the reader's limit of 16777216");
}

TEST_CASE("qp text: the dense limit is exact (4096 variables read, 4097 refused)", "[robustness][qp]") {
  CHECK(mrqp::qp::kMaxQpDenseEntries == 4096LL * 4096LL);
  std::istringstream in(identityQp(4096));
  QpText qp;
  std::string error;
  REQUIRE(mrqp::qp::readQpText(in, qp, error));
  CHECK(qp.H.rows() == 4096);
  CHECK(qp.H.diagonal().sum() == 4096.0);
  CHECK(readError(identityQp(4097)).find("line 2: n x (n + me + m) = 16785409 matrix entries") == 0);
}

TEST_CASE("qp text: a triplet count is never trusted", "[robustness][qp]") {
  // 100000000 announced entries, 1 present: the reader reaches the end of the file, it does not
  // reserve the announced count.
  const std::string text = "name a\nn 1 m 0\nP 100000000\n0 0 1\nq 0\nr 0\nC 0\nl\nu\nlb 0\nub 1\n";
  CHECK(runBounded([&] { return !readError(text).empty(); }, 64) == ChildEnd::ReturnedTrue);
  CHECK(readError(text).find("expected '<row> <column> <finite value>' in 'P'") != std::string::npos);
}

TEST_CASE("qp text: NaN is refused everywhere, infinity outside the bounds", "[robustness][qp]") {
  const std::string good =
      "name a\nn 2 m 1\nP 1\n0 0 1\nq 1 2\nr 0\nC 1\n0 1 1\nl -inf\nu 3\nlb -inf 0\nub inf 1\n";
  REQUIRE(readError(good).empty());
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return readError(s);
  };
  CHECK(with("q 1 2", "q nan 2") == "line 5: bad number 'nan' in 'q' (finite numbers only)");
  CHECK(with("q 1 2", "q inf 2") == "line 5: bad number 'inf' in 'q' (finite numbers only)");
  CHECK(with("0 0 1", "0 0 nan") == "line 4: expected '<row> <column> <finite value>' in 'P'");
  CHECK(with("0 1 1", "0 1 -inf") == "line 8: expected '<row> <column> <finite value>' in 'C'");
  CHECK(with("r 0", "r 1e999") == "line 6: 'r' needs one finite number");
  CHECK(with("u 3", "u nan") == "line 10: bad number 'nan' in 'u' (no NaN)");
  CHECK(with("ub inf 1", "ub 1e999 1") == "line 12: bad number '1e999' in 'ub' (no NaN)");
  CHECK(with("ub inf 1", "ub inf -inf").empty());
}

TEST_CASE("qp text: /dev/zero is cut at the size limit", "[robustness][qp]") {
  QpText qp;
  std::string error;
  CHECK_FALSE(mrqp::qp::readQpFile("/dev/zero", qp, error));
  CHECK(error == "/dev/zero: larger than 67108864 bytes, the limit of a QP text file");
}
