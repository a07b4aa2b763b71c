// The third-order Butterworth low-pass (see butterworth_lowpass.hpp).
#include "force/butterworth_lowpass.hpp"

#include <cmath>

namespace mrqp::force {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

bool ButterworthLowPass3::design(double cutoff_hz, double sample_hz) noexcept {
  if (!std::isfinite(cutoff_hz) || !std::isfinite(sample_hz) || !(cutoff_hz > 0.0) ||
      !(cutoff_hz < 0.5 * sample_hz)) {
    return false;
  }
  const double K = std::tan(kPi * cutoff_hz / sample_hz);  // tan(ω_c T / 2)
  const double K2 = K * K;
  s1_.b = {K / (1.0 + K), K / (1.0 + K), 0.0};
  s1_.a = {1.0, (K - 1.0) / (1.0 + K), 0.0};
  const double d = 1.0 + K + K2;
  s2_.b = {K2 / d, 2.0 * K2 / d, K2 / d};
  s2_.a = {1.0, 2.0 * (K2 - 1.0) / d, (1.0 - K + K2) / d};
  cutoff_hz_ = cutoff_hz;
  sample_hz_ = sample_hz;
  reset(0.0);
  return true;
}

double ButterworthLowPass3::step(const Section& s, std::array<double, 2>& z, double x) noexcept {
  const double y = s.b[0] * x + z[0];
  z[0] = s.b[1] * x - s.a[1] * y + z[1];
  z[1] = s.b[2] * x - s.a[2] * y;
  return y;
}

double ButterworthLowPass3::filter(double x) noexcept {
  y_ = step(s2_, z2_, step(s1_, z1_, x));
  return y_;
}

void ButterworthLowPass3::reset(double value) noexcept {
  // Each section at rest with input = output = value (unit DC gain).
  auto rest = [value](const Section& s, std::array<double, 2>& z) {
    z[1] = (s.b[2] - s.a[2]) * value;
    z[0] = (1.0 - s.b[0]) * value;
  };
  rest(s1_, z1_);
  rest(s2_, z2_);
  y_ = value;
}

bool ButterworthLowPass3::quiet(double eps) const noexcept {
  return std::fabs(y_) < eps && std::fabs(z1_[0]) < eps && std::fabs(z1_[1]) < eps &&
         std::fabs(z2_[0]) < eps && std::fabs(z2_[1]) < eps;
}

std::complex<double> ButterworthLowPass3::response(double frequency_hz) const noexcept {
  const double wT = sample_hz_ > 0.0 ? 2.0 * kPi * frequency_hz / sample_hz_ : 0.0;
  const std::complex<double> zi = std::polar(1.0, -wT);  // z⁻¹
  auto section = [&zi](const Section& s) {
    return (s.b[0] + zi * (s.b[1] + zi * s.b[2])) / (1.0 + zi * (s.a[1] + zi * s.a[2]));
  };
  return section(s1_) * section(s2_);
}

}  // namespace mrqp::force
