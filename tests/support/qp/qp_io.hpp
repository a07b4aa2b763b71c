// The QP text format (docs/qp.md, "Dump format"): the Maros–Meszaros test-set format of
// tests/data/qp/ (README there) extended by an optional block of equality rows A x = b, so that
// one reader serves the test set and QPs dumped from controller scenes.
//
//   # comment lines (only before "name")
//   name NAME
//   n <n> m <rows of C> [me <rows of A>]
//   [posdef <0|1>]                     optional
//   [objective <reference value>]      optional, includes r
//   P <nnz>                            upper triangle of H, "i j value" lines, 0-based, i <= j,
//   <i> <j> <value>                    strictly increasing in (i, j)
//   q <n values>                       g
//   r <value>                          constant term (not part of QpProblem)
//   [A <nnz> + triplets, b <me values>]  present iff me > 0
//   C <nnz> + triplets                 0-based row < m, column < n, increasing in (i, j)
//   l <m values>
//   u <m values>
//   lb <n values>
//   ub <n values>
//
// Numbers are written with %.17g (exact round trip); ±inf as inf / -inf. Host-side only: these
// functions allocate and use iostreams; never call them from the control cycle.
//
// The reader trusts nothing in the text (docs/robustness.md): it reads at most kMaxQpTextBytes,
// refuses sizes the text cannot hold (every value of q, b, l, u, lb, ub takes at least two bytes)
// before reading further, grows the triplets with the lines it reads (nothing is reserved from a
// count), and allocates the dense H, A, C only after every line has been read and checked, and
// only within kMaxQpDenseEntries. Every number must be finite, except the bounds l, u, lb, ub,
// which may be ±inf; NaN is refused everywhere.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <iosfwd>
#include <string>

#include "qp/qp_problem.hpp"

namespace mrqp::qp {

/// Largest text the reader reads (a file, or a stream such as /dev/zero), bytes.
constexpr std::size_t kMaxQpTextBytes = std::size_t{64} << 20;
/// Largest n·(n + me + m) the reader allocates for the dense H, A and C (128 MiB of doubles).
constexpr long long kMaxQpDenseEntries = 1LL << 24;

/// A QP as read from or written to text (dense, sized exactly).
struct QpText {
  std::string name;
  int n = 0, me = 0, mi = 0;
  Eigen::MatrixXd H, A, C;  ///< H symmetric (both triangles filled)
  Eigen::VectorXd g, b, l, u, xl, xu;
  double r = 0.0;              ///< constant of the objective
  bool has_objective = false;  ///< whether a reference objective was given
  double objective = 0.0;      ///< reference optimal value of ½xᵀHx + gᵀx + r
  int posdef = -1;             ///< 1 / 0 from the file, -1 when absent
};

/// Parses the text format. On failure returns false and sets `error` ("line N: ...", or "larger
/// than ... bytes" for a text over kMaxQpTextBytes); readQpFile prefixes "PATH: ".
bool readQpText(std::istream& in, QpText& out, std::string& error);
bool readQpFile(const std::string& path, QpText& out, std::string& error);

/// Writes the text format (me > 0 adds "me" and the A/b block). Returns false on a stream error.
bool writeQpText(std::ostream& out, const QpText& qp);
bool writeQpFile(const std::string& path, const QpText& qp, std::string& error);

/// Copies into a problem (resizing it); false if the QP exceeds the problem's capacity.
bool toProblem(const QpText& qp, QpProblem& problem);

/// A snapshot of the active part of a problem, for dumping (H is stored as its symmetric part).
QpText fromProblem(const QpProblem& problem, const std::string& name);

/// Writes a problem as a dump file in one call.
bool dumpProblem(const std::string& path, const QpProblem& problem, const std::string& name,
                 std::string& error);

/// ½xᵀHx + gᵀx + r evaluated from the text data.
double evaluateObjective(const QpText& qp, const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace mrqp::qp
