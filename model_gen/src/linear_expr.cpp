#include "linear_expr.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace mrqp::gen {

std::string literal(double x) {
  if (x == 0.0) return "0.0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  std::string s(buf);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

double snap(double x) {
  constexpr double eps = 1e-14;
  if (std::abs(x) < eps) return 0.0;
  if (std::abs(x - 1.0) < eps) return 1.0;
  if (std::abs(x + 1.0) < eps) return -1.0;
  return x;
}

LinearExpr& LinearExpr::add(double coef, const std::string& symbol) {
  coef = snap(coef);
  if (coef == 0.0) return *this;
  for (auto& t : terms_) {
    if (t.second == symbol) {
      t.first = snap(t.first + coef);
      return *this;
    }
  }
  terms_.emplace_back(coef, symbol);
  return *this;
}

bool LinearExpr::empty() const {
  for (const auto& t : terms_)
    if (t.first != 0.0) return false;
  return true;
}

std::string LinearExpr::str() const {
  std::string out;
  for (const auto& [c, sym] : terms_) {
    if (c == 0.0) continue;
    const bool neg = c < 0.0;
    const double a = neg ? -c : c;
    std::string term;
    if (sym.empty())
      term = literal(a);
    else if (a == 1.0)
      term = sym;
    else
      term = literal(a) + " * " + sym;
    if (out.empty())
      out = neg ? "-" + term : term;
    else
      out += (neg ? " - " : " + ") + term;
  }
  return out.empty() ? "0.0" : out;
}

}  // namespace mrqp::gen
