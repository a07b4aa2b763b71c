#include "qp/qp_io.hpp"

#include <cerrno>
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

// Reads the file line by line and splits each line on spaces.
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

bool parseDouble(const std::string& s, double& v) {
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  v = std::strtod(begin, &end);
  return end != begin && *end == '\0' && errno != ERANGE;
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

struct Parser {
  LineReader reader;
  std::string& error;
  std::vector<std::string> tok;
  bool have = false;  // tok holds a line not consumed yet

  Parser(std::istream& in, std::string& err) : reader(in), error(err) {}

  bool fail(const std::string& msg) {
    error = "line " + std::to_string(reader.line()) + ": " + msg;
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
    if (tok.size() != 2 || !parseDouble(tok[1], v))
      return fail(std::string("'") + key + "' needs one number");
    return true;
  }
  bool vectorLine(const char* key, int size, Eigen::VectorXd& v) {
    if (!expect(key)) return false;
    if (static_cast<int>(tok.size()) != size + 1)
      return fail(std::string("'") + key + "' needs " + std::to_string(size) + " values, found " +
                  std::to_string(tok.size() - 1));
    v.resize(size);
    for (int i = 0; i < size; ++i)
      if (!parseDouble(tok[static_cast<std::size_t>(i) + 1], v(i)))
        return fail(std::string("bad number '") + tok[static_cast<std::size_t>(i) + 1] + "' in '" + key +
                    "'");
    return true;
  }
  // "<key> <nnz>" followed by nnz "i j v" lines, strictly increasing in (i, j).
  bool tripletBlock(const char* key, int rows, int cols, bool upper, Eigen::MatrixXd& M) {
    if (!expect(key)) return false;
    int nnz = 0;
    if (tok.size() != 2 || !parseInt(tok[1], nnz))
      return fail(std::string("'") + key + "' needs a non-negative count");
    M.setZero(rows, cols);
    long prev = -1;
    for (int k = 0; k < nnz; ++k) {
      if (!reader.next(tok)) return fail(std::string("unexpected end of file in '") + key + "'");
      int i = 0, j = 0;
      double v = 0.0;
      if (tok.size() != 3 || !parseInt(tok[0], i) || !parseInt(tok[1], j) || !parseDouble(tok[2], v))
        return fail(std::string("expected '<row> <column> <value>' in '") + key + "'");
      if (i >= rows || j >= cols) return fail(std::string("index out of range in '") + key + "'");
      if (upper && i > j) return fail(std::string("'") + key + "' must hold the upper triangle (i <= j)");
      const long pos = static_cast<long>(i) * cols + j;
      if (pos <= prev) return fail(std::string("entries of '") + key + "' must be sorted and unique");
      prev = pos;
      M(i, j) = v;
      if (upper) M(j, i) = v;
    }
    return true;
  }
};

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
  Parser p(in, error);
  QpText qp;
  if (!p.expect("name")) return false;
  if (p.tok.size() != 2) return p.fail("'name' needs one token");
  qp.name = p.tok[1];
  if (!p.expect("n")) return false;
  if ((p.tok.size() != 4 && p.tok.size() != 6) || !parseInt(p.tok[1], qp.n) || p.tok[2] != "m" ||
      !parseInt(p.tok[3], qp.mi) || (p.tok.size() == 6 && (p.tok[4] != "me" || !parseInt(p.tok[5], qp.me))))
    return p.fail("expected 'n <n> m <m> [me <me>]'");
  if (p.peekIs("posdef")) {
    double v = 0.0;
    if (!p.scalarLine("posdef", v) || (v != 0.0 && v != 1.0)) return p.fail("'posdef' must be 0 or 1");
    qp.posdef = static_cast<int>(v);
  }
  if (p.peekIs("objective")) {
    if (!p.scalarLine("objective", qp.objective)) return false;
    qp.has_objective = true;
  }
  if (!p.tripletBlock("P", qp.n, qp.n, true, qp.H)) return false;
  if (!p.vectorLine("q", qp.n, qp.g)) return false;
  if (!p.scalarLine("r", qp.r)) return false;
  if (qp.me > 0) {
    if (!p.tripletBlock("A", qp.me, qp.n, false, qp.A)) return false;
    if (!p.vectorLine("b", qp.me, qp.b)) return false;
  } else {
    qp.A.resize(0, qp.n);
    qp.b.resize(0);
  }
  if (!p.tripletBlock("C", qp.mi, qp.n, false, qp.C)) return false;
  if (!p.vectorLine("l", qp.mi, qp.l)) return false;
  if (!p.vectorLine("u", qp.mi, qp.u)) return false;
  if (!p.vectorLine("lb", qp.n, qp.xl)) return false;
  if (!p.vectorLine("ub", qp.n, qp.xu)) return false;
  if (p.peek()) return p.fail("unexpected '" + p.tok[0] + "' after 'ub'");
  out = std::move(qp);
  return true;
}

bool readQpFile(const std::string& path, QpText& out, std::string& error) {
  std::ifstream in(path);
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
