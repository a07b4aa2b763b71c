// A linear combination of symbols with constant coefficients, printed as C++ with zero terms
// dropped and unit coefficients folded: how the generator specialises code to constant
// axes, placements and inertias.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mrqp::gen {

/// Formats a double so that it reads back bit-exactly ("%.17g"), as a floating literal.
std::string literal(double x);

/// Rounds values within 1e-14 of 0, 1 or -1 to them (rotation matrices computed from rpy angles
/// carry such noise); everything else is kept exactly.
double snap(double x);

class LinearExpr {
 public:
  LinearExpr() = default;
  /// Adds coef·symbol; an empty symbol is the constant term.
  LinearExpr& add(double coef, const std::string& symbol);
  bool empty() const;
  /// C++ text of the sum, "0.0" when every coefficient is zero.
  std::string str() const;

 private:
  std::vector<std::pair<double, std::string>> terms_;
};

}  // namespace mrqp::gen
