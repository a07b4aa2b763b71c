/* mrqp firmware interface -- NaN tests, saturation and quantisation. */
#include "mrqp/firmware_if/saturate.h"

#include <string.h>

int mrqp_fw_isnan_d(double x) {
  uint64_t bits;
  memcpy(&bits, &x, sizeof(bits));
  return (bits & 0x7FF0000000000000u) == 0x7FF0000000000000u && (bits & 0x000FFFFFFFFFFFFFu) != 0u;
}

int mrqp_fw_isnan_f(float x) {
  uint32_t bits;
  memcpy(&bits, &x, sizeof(bits));
  return (bits & 0x7F800000u) == 0x7F800000u && (bits & 0x007FFFFFu) != 0u;
}

int mrqp_fw_isfinite_d(double x) {
  uint64_t bits;
  memcpy(&bits, &x, sizeof(bits));
  return (bits & 0x7FF0000000000000u) != 0x7FF0000000000000u;
}

int mrqp_fw_isfinite_f(float x) {
  uint32_t bits;
  memcpy(&bits, &x, sizeof(bits));
  return (bits & 0x7F800000u) != 0x7F800000u;
}

/* Round half away from zero; |x| < 2^62. x - trunc(x) is exact for doubles. */
static int64_t round_away(double x) {
  int64_t t = (int64_t)x; /* truncation toward zero */
  double frac = x - (double)t;
  if (frac >= 0.5) {
    ++t;
  } else if (frac <= -0.5) {
    --t;
  }
  return t;
}

mrqp_fw_conv mrqp_fw_quantize_int(double x, int64_t lo, int64_t hi, int64_t* out) {
  if (mrqp_fw_isnan_d(x)) {
    return MRQP_FW_CONV_NAN;
  }
  /* hi + 0.5 and lo - 0.5 are exact for |lo|, |hi| <= 2^52. */
  if (x >= (double)hi + 0.5) {
    *out = hi;
    return MRQP_FW_CONV_SAT_HIGH;
  }
  if (x <= (double)lo - 0.5) {
    *out = lo;
    return MRQP_FW_CONV_SAT_LOW;
  }
  /* lo - 1/2 < x < hi + 1/2: rounding half away from zero lands in [lo, hi]. */
  *out = round_away(x);
  if (*out > hi) { /* only reachable through a tie at hi + 1/2, excluded above; kept as a guard */
    *out = hi;
  } else if (*out < lo) {
    *out = lo;
  }
  return MRQP_FW_CONV_OK;
}

static double max_code(unsigned bits) { return (double)((((uint64_t)1u) << bits) - 1u); }

mrqp_fw_conv mrqp_fw_quantize_linear(double x, double min, double max, unsigned bits, uint32_t* code) {
  double top;
  int64_t c = 0;
  mrqp_fw_conv r;
  double u;
  if (bits < 1u || bits > 32u || !mrqp_fw_isfinite_d(min) || !mrqp_fw_isfinite_d(max) || !(min < max)) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  if (mrqp_fw_isnan_d(x)) {
    return MRQP_FW_CONV_NAN;
  }
  top = max_code(bits);
  u = (x - min) / (max - min) * top; /* +/-inf for infinite x: saturates */
  r = mrqp_fw_quantize_int(u, 0, (int64_t)top, &c);
  *code = (uint32_t)c;
  return r;
}

double mrqp_fw_dequantize_linear(uint32_t code, double min, double max, unsigned bits) {
  return min + (double)code * (max - min) / max_code(bits);
}

mrqp_fw_conv mrqp_fw_quantize_fixed(double x, double lsb, unsigned bits, int32_t* code) {
  int64_t lim;
  int64_t c = 0;
  mrqp_fw_conv r;
  if (bits < 2u || bits > 32u || !mrqp_fw_isfinite_d(lsb) || !(lsb > 0.0)) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  if (mrqp_fw_isnan_d(x)) {
    return MRQP_FW_CONV_NAN;
  }
  lim = (int64_t)((((uint64_t)1u) << (bits - 1u)) - 1u);
  r = mrqp_fw_quantize_int(x / lsb, -lim, lim, &c);
  *code = (int32_t)c;
  return r;
}

double mrqp_fw_dequantize_fixed(int32_t code, double lsb) { return (double)code * lsb; }
