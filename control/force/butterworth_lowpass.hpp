// The third-order Butterworth low-pass of the force admittance (Sec. III, Fig. 4: "order 3, cutoff
// frequency 20 Hz"; docs/force-control.md), designed for a cutoff f_c and a sample rate f_s by the
// bilinear transform with prewarping. The analog prototype
//
//   H(s) = 1 / ((s/Ω_c + 1)(s²/Ω_c² + s/Ω_c + 1)),   |H(jΩ)| = 1 / √(1 + (Ω/Ω_c)⁶),
//
// with Ω_c = (2/T) tan(ω_c T/2) (prewarped, T = 1/f_s) becomes, through s = (2/T)(z − 1)/(z + 1),
// a first-order section and a biquad in cascade. With K = tan(ω_c T/2):
//
//   first order   b = K/(1+K) [1, 1],                a₁ = (K−1)/(1+K)
//   second order  b = K²/(1+K+K²) [1, 2, 1],         a₁ = 2(K²−1)/(1+K+K²),  a₂ = (1−K+K²)/(1+K+K²)
//
// so that the digital response at ω equals the analog one at Ω = (2/T) tan(ωT/2): exactly −3 dB at
// f_c, unit gain at DC. Coefficients are computed once by design(); filter() is plain arithmetic
// (noexcept, allocation-free), in transposed direct form II.
#pragma once

#include <array>
#include <complex>

namespace mrqp::force {

class ButterworthLowPass3 {
 public:
  /// An identity filter until design() is called.
  ButterworthLowPass3() = default;

  /// Designs the filter: false (and unchanged) unless 0 < cutoff_hz < sample_hz / 2, both finite.
  bool design(double cutoff_hz, double sample_hz) noexcept;

  /// One sample in, one out.
  double filter(double x) noexcept;
  /// The state of a filter that has seen `value` forever (output `value` until the input changes).
  void reset(double value = 0.0) noexcept;
  /// The last output.
  double output() const noexcept { return y_; }
  /// Output and state all below `eps` in magnitude (a decay that has ended).
  bool quiet(double eps) const noexcept;

  /// The digital frequency response H(e^{jωT}) at ω = 2π·frequency_hz (for tests and docs).
  std::complex<double> response(double frequency_hz) const noexcept;

  double cutoff() const noexcept { return cutoff_hz_; }
  double sampleRate() const noexcept { return sample_hz_; }

  /// Coefficients of the two sections: b[0..2], a[1..2] (a[0] = 1; the first-order section has
  /// b[2] = a[2] = 0).
  struct Section {
    std::array<double, 3> b{{1.0, 0.0, 0.0}};
    std::array<double, 3> a{{1.0, 0.0, 0.0}};
  };
  const Section& first() const noexcept { return s1_; }
  const Section& second() const noexcept { return s2_; }

 private:
  static double step(const Section& s, std::array<double, 2>& z, double x) noexcept;

  Section s1_, s2_;
  std::array<double, 2> z1_{}, z2_{};  // transposed direct form II state per section
  double y_ = 0.0;
  double cutoff_hz_ = 0.0, sample_hz_ = 0.0;
};

}  // namespace mrqp::force
