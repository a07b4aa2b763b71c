// The admittance's third-order Butterworth low-pass (control/force/butterworth_lowpass.hpp)
// against the analog prototype in closed form:
//   |H(jΩ)| = 1/√(1 + (Ω/Ω_c)⁶),  arg H(jΩ) = −atan(x) − atan2(x, 1 − x²),  x = Ω/Ω_c,
//   step response y(t) = 1 − e^{−ω_c t} − (2/√3) e^{−ω_c t/2} sin(√3 ω_c t/2),
// the digital response through the bilinear frequency map Ω = (2/T) tan(ωT/2) (prewarping makes
// Ω_c = (2/T) tan(ω_c T/2)), and measured with sines run through filter().
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>

#include "force/butterworth_lowpass.hpp"

using mrqp::force::ButterworthLowPass3;

namespace {

constexpr double kPi = 3.14159265358979323846;

double analogMagnitude(double x) { return 1.0 / std::sqrt(1.0 + std::pow(x, 6)); }
double analogPhase(double x) { return -std::atan(x) - std::atan2(x, 1.0 - x * x); }
/// x = Ω/Ω_c of a digital frequency f through the bilinear map, prewarped at f_c.
double warped(double f, double fc, double fs) { return std::tan(kPi * f / fs) / std::tan(kPi * fc / fs); }
double analogStep(double t, double fc) {
  const double w = 2.0 * kPi * fc * t;
  return 1.0 - std::exp(-w) - 2.0 / std::sqrt(3.0) * std::exp(-w / 2.0) * std::sin(std::sqrt(3.0) * w / 2.0);
}

}  // namespace

TEST_CASE("force: Butterworth response is the analog prototype's through the bilinear map",
          "[force][filter]") {
  for (double fs : {1000.0, 250.0, 100.0}) {
    ButterworthLowPass3 f;
    REQUIRE(f.design(20.0, fs));
    for (double freq : {0.0, 1.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 0.45 * fs}) {
      INFO("fs = " << fs << ", f = " << freq);
      const std::complex<double> h = f.response(freq);
      const double x = warped(freq, 20.0, fs);
      CHECK(std::abs(h) == Approx(analogMagnitude(x)).epsilon(1e-10).margin(1e-12));
      if (freq > 0.0) CHECK(std::arg(h) == Approx(std::remainder(analogPhase(x), 2 * kPi)).margin(1e-9));
    }
    // Prewarping: exactly −3 dB at the cutoff; unit gain at DC.
    CHECK(std::abs(f.response(20.0)) == Approx(1.0 / std::sqrt(2.0)).epsilon(1e-12));
    CHECK(std::abs(f.response(0.0)) == Approx(1.0).epsilon(1e-12));
  }
  // At 1 kHz the warping is small: the unwarped analog magnitude within 0.3 % of full scale.
  ButterworthLowPass3 f;
  REQUIRE(f.design(20.0, 1000.0));
  for (double freq : {5.0, 10.0, 20.0, 30.0, 40.0}) {
    CHECK(std::abs(f.response(freq)) == Approx(analogMagnitude(freq / 20.0)).margin(3e-3));
  }
}

TEST_CASE("force: Butterworth filtering a sine: measured gain and phase", "[force][filter]") {
  const double fs = 1000.0, fc = 20.0;
  for (double freq : {2.0, 10.0, 20.0, 35.0, 60.0}) {
    INFO("f = " << freq);
    ButterworthLowPass3 f;
    REQUIRE(f.design(fc, fs));
    // Settle for 2 s, then fit a sin + b cos over a whole number of periods (1 s).
    const int settle = 2000, n = 1000;
    double a = 0.0, b = 0.0;
    for (int k = 0; k < settle + n; ++k) {
      const double wt = 2.0 * kPi * freq * k / fs;
      const double y = f.filter(std::sin(wt));
      if (k >= settle) {
        a += 2.0 / n * y * std::sin(wt);
        b += 2.0 / n * y * std::cos(wt);
      }
    }
    const double x = warped(freq, fc, fs);
    CHECK(std::hypot(a, b) == Approx(analogMagnitude(x)).margin(1e-6));
    CHECK(std::atan2(b, a) == Approx(std::remainder(analogPhase(x), 2 * kPi)).margin(1e-6));
  }
}

TEST_CASE("force: Butterworth step response follows the analog one", "[force][filter]") {
  // The bilinear transform is the trapezoidal rule: its step response is the analog one sampled
  // half a sample late, with an error of second order in T (measured: 7.9e-4 at 1 kHz, 8e-6 at
  // 10 kHz for a 20 Hz cutoff).
  for (const auto& [fs, tol] : {std::pair<double, double>{1000.0, 1.5e-3}, {10000.0, 2e-5}}) {
    INFO("fs = " << fs);
    ButterworthLowPass3 f;
    REQUIRE(f.design(20.0, fs));
    double worst = 0.0, overshoot = 0.0;
    for (int k = 0; k < static_cast<int>(0.3 * fs); ++k) {
      const double y = f.filter(1.0);
      worst = std::max(worst, std::fabs(y - analogStep((k + 0.5) / fs, 20.0)));
      overshoot = std::max(overshoot, y - 1.0);
    }
    CHECK(worst < tol);
    // The third-order Butterworth overshoots by 8.15 %.
    CHECK(overshoot == Approx(0.0815).margin(2e-3));
    CHECK(f.output() == Approx(1.0).margin(1e-6));
  }
}

TEST_CASE("force: Butterworth reset, quiet state and design limits", "[force][filter]") {
  ButterworthLowPass3 f;
  REQUIRE(f.design(20.0, 1000.0));
  f.reset(0.3);
  for (int k = 0; k < 100; ++k) CHECK(f.filter(0.3) == Approx(0.3).epsilon(1e-14));
  CHECK_FALSE(f.quiet(1e-15));
  f.reset(0.0);
  CHECK(f.quiet(1e-15));
  // No design at or above Nyquist, at zero, negative or non-finite cutoffs; the filter is unchanged.
  CHECK_FALSE(f.design(500.0, 1000.0));
  CHECK_FALSE(f.design(0.0, 1000.0));
  CHECK_FALSE(f.design(-1.0, 1000.0));
  CHECK_FALSE(f.design(std::nan(""), 1000.0));
  CHECK_FALSE(f.design(20.0, std::numeric_limits<double>::infinity()));
  CHECK(f.cutoff() == 20.0);
  CHECK(f.sampleRate() == 1000.0);
}
