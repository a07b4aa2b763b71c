#include "qp/qp_io.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>
#include <utility>
#include <vector>

namespace mrqp::qp {

namespace {

// Reads the text line by line and splits each line on spaces.
class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(in) {}

  // Next non-empty line; comment lines are allowed only before the first keyword.
  bool next(std::vector<std::string>& tokens) {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty()) continue;
      if (line[0] == '#' && !started_) continue;
      started_ = true;
      tokens.clear();
      std::istringstream ss(line);
      std::string t;
      while (ss >> t) tokens.push_back(t);
      if (tokens.empty()) continue;
      return true;
    }
    return false;
  }
  int line() const { return number_; }

 private:
  std::istream& in_;
  int number_ = 0;
  bool started_ = false;
};

// Which values a number may take where it is read.
enum class Range { Finite, NotNan };

bool parseDouble(const std::string& s, double& v, Range range) {
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  v = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || std::isnan(v)) return false;
  // ±inf only as written ("inf", "-inf"), never a finite number that overflows (1e999); an
  // underflow to a subnormal or zero is the nearest double and is kept.
  if (std::isinf(v)) return range == Range::NotNan && errno != ERANGE;
  return true;
}

bool parseInt(const std::string& s, int& v) {
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(begin, &end, 10);
  if (end == begin || *end != '\0' || errno == ERANGE || x < 0 || x > 100000000) return false;
  v = static_cast<int>(x);
  return true;
}

struct Triplet {
  int i, j;
  double v;
};

// Phase one reads every line into these light structures (their size follows the data the text
// holds); phase two checks the dense size and only then allocates the matrices.
struct Parsed {
  std::vector<Triplet> P, A, C;
};

struct Parser {
  LineReader reader;
  std::string& error;
  std::vector<std::string> tok;
  bool have = false;  // tok holds a line not consumed yet

  Parser(std::istream& in, std::string& err) : reader(in), error(err) {}

  bool fail(const std::string& msg) { return failAt(reader.line(), msg); }
  bool failAt(int line, const std::string& msg) {
    error = "line " + std::to_string(line) + ": " + msg;
    return false;
  }
  bool peek() {
    if (!have) have = reader.next(tok);
    return have;
  }
  // The next line must start with `key`; its tokens are left in tok.
  bool expect(const char* key) {
    if (!peek()) return fail(std::string("unexpected end of file, expected '") + key + "'");
    if (tok[0] != key) return fail(std::string("expected '") + key + "', found '" + tok[0] + "'");
    have = false;
    return true;
  }
  bool peekIs(const char* key) { return peek() && tok[0] == key; }

  bool scalarLine(const char* key, double& v) {
    if (!expect(key)) return false;
    if (tok.size() != 2 || !parseDouble(tok[1], v, Range::Finite))
      return fail(std::string("'") + key + "' needs one finite number");
    return true;
  }
  // The line's length is checked before the vector is sized: a size comes from the data.
  bool vectorLine(const char* key, int size, Range range, Eigen::VectorXd& v) {
    if (!expect(key)) return false;
    if (tok.size() != static_cast<std::size_t>(size) + 1)
      return fail(std::string("'") + key + "' needs " + std::to_string(size) + " values, found " +
                  std::to_string(tok.size() - 1));
    v.resize(size);
    for (int i = 0; i < size; ++i)
      if (!parseDouble(tok[static_cast<std::size_t>(i) + 1], v(i), range))
        return fail(std::string("bad number '") + tok[static_cast<std::size_t>(i) + 1] + "' in '" + key +
                    "'" + (range == Range::Finite ? " (finite numbers only)" : " (no NaN)"));
    return true;
  }
  // "<key> <nnz>" followed by nnz "i j v" lines, strictly increasing in (i, j). Nothing is
  // reserved from nnz: the triplets grow with the lines actually read.
  bool tripletBlock(const char* key, int rows, int cols, bool upper, std::vector<Triplet>& out) {
    if (!expect(key)) return false;
    int nnz = 0;
    if (tok.size() != 2 || !parseInt(tok[1], nnz))
      return fail(std::string("'") + key + "' needs a non-negative count");
    long long prev = -1;
    for (int k = 0; k < nnz; ++k) {
      if (!reader.next(tok)) return fail(std::string("unexpected end of file in '") + key + "'");
      int i = 0, j = 0;
      double v = 0.0;
      if (tok.size() != 3 || !parseInt(tok[0], i) || !parseInt(tok[1], j) ||
          !parseDouble(tok[2], v, Range::Finite))
        return fail(std::string("expected '<row> <column> <finite value>' in '") + key + "'");
      if (i >= rows || j >= cols) return fail(std::string("index out of range in '") + key + "'");
      if (upper && i > j) return fail(std::string("'") + key + "' must hold the upper triangle (i <= j)");
      const long long pos = static_cast<long long>(i) * cols + j;
      if (pos <= prev) return fail(std::string("entries of '") + key + "' must be sorted and unique");
      prev = pos;
      out.push_back(Triplet{i, j, v});
    }
    return true;
  }
};

void fill(const std::vector<Triplet>& triplets, int rows, int cols, bool symmetric, Eigen::MatrixXd& M) {
  M.setZero(rows, cols);
  for (const Triplet& t : triplets) {
    M(t.i, t.j) = t.v;
    if (symmetric) M(t.j, t.i) = t.v;
  }
}

// The whole text, at most kMaxQpTextBytes: false when there is more (/dev/zero).
bool readBounded(std::istream& in, std::string& text) {
  text.clear();
  char buffer[65536];
  for (;;) {
    in.read(buffer, sizeof buffer);
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) return true;
    if (got > kMaxQpTextBytes - text.size()) return false;
    text.append(buffer, got);
  }
}

void writeNumber(std::ostream& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out << buf;
}

void writeVector(std::ostream& out, const char* key, const Eigen::VectorXd& v) {
  out << key;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    out << ' ';
    writeNumber(out, v(i));
  }
  out << '\n';
}

void writeTriplets(std::ostream& out, const char* key, const Eigen::MatrixXd& M, bool upper) {
  long nnz = 0;
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = upper ? i : 0; j < M.cols(); ++j) nnz += M(i, j) != 0.0;
  out << key << ' ' << nnz << '\n';
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = upper ? i : 0; j < M.cols(); ++j)
      if (M(i, j) != 0.0) {
        out << i << ' ' << j << ' ';
        writeNumber(out, M(i, j));
        out << '\n';
      }
}

}  // namespace

bool readQpText(std::istream& in, QpText& out, std::string& error) {
  std::string text;
  if (!readBounded(in, text)) {
    error = "larger than " + std::to_string(kMaxQpTextBytes) + " bytes, the limit of a QP text file";
    return false;
  }
  std::istringstream lines(text);
  Parser p(lines, error);
  QpText qp;
  Parsed parsed;
  if (!p.expect("name")) return false;
  if (p.tok.size() != 2) return p.fail("'name' needs one token");
  qp.name = p.tok[1];
  if (!p.expect("n")) return false;
  if ((p.tok.size() != 4 && p.tok.size() != 6) || !parseInt(p.tok[1], qp.n) || p.tok[2] != "m" ||
      !parseInt(p.tok[3], qp.mi) || (p.tok.size() == 6 && (p.tok[4] != "me" || !parseInt(p.tok[5], qp.me))))
    return p.fail("expected 'n <n> m <m> [me <me>]'");
  const int header_line = p.reader.line();
  // The vectors q, lb, ub (n values each), l, u (m) and b (me) take at least two bytes a value:
  // sizes the text cannot hold are refused before anything is read or allocated.
  const long long values = 3LL * qp.n + 2LL * qp.mi + qp.me;
  if (2 * values > static_cast<long long>(text.size()))
    return p.fail("n " + std::to_string(qp.n) + ", m " + std::to_string(qp.mi) + ", me " +
                  std::to_string(qp.me) + " need at least " + std::to_string(2 * values) +
                  " bytes of values; the file holds " + std::to_string(text.size()));
  if (p.peekIs("posdef")) {
    double v = 0.0;
    if (!p.scalarLine("posdef", v) || (v != 0.0 && v != 1.0)) return p.fail("'posdef' must be 0 or 1");
    qp.posdef = static_cast<int>(v);
  }
  if (p.peekIs("objective")) {
    if (!p.scalarLine("objective", qp.objective)) return false;
    qp.has_objective = true;
  }
  if (!p.tripletBlock("P", qp.n, qp.n, true, parsed.P)) return false;
  if (!p.vectorLine("q", qp.n, Range::Finite, qp.g)) return false;
  if (!p.scalarLine("r", qp.r)) return false;
  if (qp.me > 0) {
    if (!p.tripletBlock("A", qp.me, qp.n, false, parsed.A)) return false;
    if (!p.vectorLine("b", qp.me, Range::Finite, qp.b)) return false;
  } else {
    qp.b.resize(0);
  }
  if (!p.tripletBlock("C", qp.mi, qp.n, false, parsed.C)) return false;
  if (!p.vectorLine("l", qp.mi, Range::NotNan, qp.l)) return false;
  if (!p.vectorLine("u", qp.mi, Range::NotNan, qp.u)) return false;
  if (!p.vectorLine("lb", qp.n, Range::NotNan, qp.xl)) return false;
  if (!p.vectorLine("ub", qp.n, Range::NotNan, qp.xu)) return false;
  if (p.peek()) return p.fail("unexpected '" + p.tok[0] + "' after 'ub'");
  // The dense matrices H (n×n), A (me×n) and C (m×n), only now, and only within the limit.
  const long long entries = static_cast<long long>(qp.n) * (static_cast<long long>(qp.n) + qp.me + qp.mi);
  if (entries > kMaxQpDenseEntries)
    return p.failAt(header_line, "n x (n + me + m) = " + std::to_string(entries) +
                                     " matrix entries, more than the reader's limit of " +
                                     std::to_string(kMaxQpDenseEntries));
  fill(parsed.P, qp.n, qp.n, true, qp.H);
  fill(parsed.A, qp.me, qp.n, false, qp.A);
  fill(parsed.C, qp.mi, qp.n, false, qp.C);
  out = std::move(qp);
  return true;
}

bool readQpFile(const std::string& path, QpText& out, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open";
    return false;
  }
  if (!readQpText(in, out, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

bool writeQpText(std::ostream& out, const QpText& qp) {
  // the name is one token
  std::string name = qp.name.empty() ? std::string("unnamed") : qp.name;
  for (char& c : name)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = '_';
  out << "# mrqp QP dump " << name
      << " — minimize 1/2 x'Px + q'x + r subject to Ax = b, l <= Cx <= u, lb <= x <= ub\n";
  out << "name " << name << '\n';
  out << "n " << qp.n << " m " << qp.mi;
  if (qp.me > 0) out << " me " << qp.me;
  out << '\n';
  if (qp.posdef >= 0) out << "posdef " << qp.posdef << '\n';
  if (qp.has_objective) {
    out << "objective ";
    writeNumber(out, qp.objective);
    out << '\n';
  }
  writeTriplets(out, "P", qp.H, true);
  writeVector(out, "q", qp.g);
  out << "r ";
  writeNumber(out, qp.r);
  out << '\n';
  if (qp.me > 0) {
    writeTriplets(out, "A", qp.A, false);
    writeVector(out, "b", qp.b);
  }
  writeTriplets(out, "C", qp.C, false);
  writeVector(out, "l", qp.l);
  writeVector(out, "u", qp.u);
  writeVector(out, "lb", qp.xl);
  writeVector(out, "ub", qp.xu);
  return static_cast<bool>(out);
}

bool writeQpFile(const std::string& path, const QpText& qp, std::string& error) {
  std::ofstream out(path);
  if (!out || !writeQpText(out, qp)) {
    error = path + ": cannot write";
    return false;
  }
  out.close();
  if (!out) {
    error = path + ": cannot write";
    return false;
  }
  return true;
}

bool toProblem(const QpText& qp, QpProblem& problem) {
  if (!problem.resize(qp.n, qp.me, qp.mi)) return false;
  problem.H() = qp.H;
  problem.g() = qp.g;
  problem.A() = qp.A;
  problem.b() = qp.b;
  problem.C() = qp.C;
  problem.l() = qp.l;
  problem.u() = qp.u;
  problem.xl() = qp.xl;
  problem.xu() = qp.xu;
  return true;
}

QpText fromProblem(const QpProblem& problem, const std::string& name) {
  QpText qp;
  qp.name = name;
  qp.n = problem.n();
  qp.me = problem.me();
  qp.mi = problem.mi();
  qp.H = 0.5 * (problem.H() + problem.H().transpose());
  qp.g = problem.g();
  qp.A = problem.A();
  qp.b = problem.b();
  qp.C = problem.C();
  qp.l = problem.l();
  qp.u = problem.u();
  qp.xl = problem.xl();
  qp.xu = problem.xu();
  return qp;
}

bool dumpProblem(const std::string& path, const QpProblem& problem, const std::string& name,
                 std::string& error) {
  return writeQpFile(path, fromProblem(problem, name), error);
}

double evaluateObjective(const QpText& qp, const Eigen::Ref<const Eigen::VectorXd>& x) {
  return 0.5 * x.dot(qp.H * x) + qp.g.dot(x) + qp.r;
}

}  // namespace mrqp::qp
