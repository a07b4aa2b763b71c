// libFuzzer harness: the QP text reader (tests/support/qp/qp_io.hpp, docs/qp.md "Dump format").
//
// Properties beyond "no crash, no undefined behaviour, no allocation beyond libFuzzer's limit":
// a QP that reads has the sizes its header declares (H symmetric n×n, every vector and matrix to
// match), and writing it and reading it back gives the same QP bit for bit (the writer's %.17g
// round trip), so the reader accepts nothing the writer cannot express.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_check.hpp"
#include "qp/qp_io.hpp"

namespace {

bool sameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double x = a.data()[i], y = b.data()[i];
    if (!(x == y || (x != x && y != y))) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  mrqp::qp::QpText qp;
  std::string error;
  if (!mrqp::qp::readQpText(in, qp, error)) {
    MRQP_FUZZ_CHECK(!error.empty());
    return 0;
  }
  const Eigen::Index n = qp.n, me = qp.me, mi = qp.mi;
  MRQP_FUZZ_CHECK(qp.H.rows() == n && qp.H.cols() == n);
  MRQP_FUZZ_CHECK(sameBits(qp.H, qp.H.transpose()));
  MRQP_FUZZ_CHECK(qp.g.size() == n && qp.xl.size() == n && qp.xu.size() == n);
  MRQP_FUZZ_CHECK(qp.A.rows() == me && qp.A.cols() == n && qp.b.size() == me);
  MRQP_FUZZ_CHECK(qp.C.rows() == mi && qp.C.cols() == n && qp.l.size() == mi && qp.u.size() == mi);

  std::ostringstream out;
  MRQP_FUZZ_CHECK(mrqp::qp::writeQpText(out, qp));
  std::istringstream again(out.str());
  mrqp::qp::QpText back;
  MRQP_FUZZ_CHECK(mrqp::qp::readQpText(again, back, error));
  MRQP_FUZZ_CHECK(back.n == qp.n && back.me == qp.me && back.mi == qp.mi);
  MRQP_FUZZ_CHECK(sameBits(back.H, qp.H) && sameBits(back.A, qp.A) && sameBits(back.C, qp.C));
  MRQP_FUZZ_CHECK(sameBits(back.g, qp.g) && sameBits(back.b, qp.b) && sameBits(back.l, qp.l) &&
                  sameBits(back.u, qp.u) && sameBits(back.xl, qp.xl) && sameBits(back.xu, qp.xu));
  return 0;
}
