/*
 * mrqp firmware interface -- NaN tests, saturation and quantisation shared by all messages.
 *
 * Rounding is to the nearest code, ties away from zero. The NaN tests inspect the bit pattern,
 * so they keep working under -ffast-math. A value whose nearest code lies outside the range (more
 * than half a step beyond an end, exactly half a step included, or +/-infinity) is clamped to that
 * end and reported as saturated; any other value is within half a step of its code.
 */
#ifndef MRQP_FIRMWARE_IF_SATURATE_H
#define MRQP_FIRMWARE_IF_SATURATE_H

#include <stdint.h>

#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Non-zero if x is a NaN (any payload, either sign). */
int mrqp_fw_isnan_d(double x);
int mrqp_fw_isnan_f(float x);
/** Non-zero if x is neither NaN nor infinite. */
int mrqp_fw_isfinite_d(double x);
int mrqp_fw_isfinite_f(float x);

/**
 * Rounds x to an integer in [lo, hi] (|lo|, |hi| <= 2^52).
 * Returns CONV_OK, CONV_SAT_LOW / CONV_SAT_HIGH (x <= lo - 1/2 or x >= hi + 1/2: *out = lo or hi)
 * or CONV_NAN (*out not written).
 */
mrqp_fw_conv mrqp_fw_quantize_int(double x, int64_t lo, int64_t hi, int64_t* out);

/**
 * Linear map of [min, max] onto the unsigned codes 0 .. 2^bits - 1 (1 <= bits <= 32):
 * code = round((x - min) / (max - min) * (2^bits - 1)). x more than half a step outside
 * [min, max] saturates.
 * Returns CONV_BAD_SCALE (nothing written) unless min < max, both finite.
 * Quantisation error inside the range: at most (max - min) / (2 (2^bits - 1)).
 */
mrqp_fw_conv mrqp_fw_quantize_linear(double x, double min, double max, unsigned bits, uint32_t* code);
/** Inverse of mrqp_fw_quantize_linear: min + code (max - min) / (2^bits - 1). */
double mrqp_fw_dequantize_linear(uint32_t code, double min, double max, unsigned bits);

/**
 * Signed fixed point: code = round(x / lsb), limited to the symmetric range
 * +/-(2^(bits-1) - 1) (2 <= bits <= 32); the most negative two's complement code is reserved as
 * "invalid" and never produced. Returns CONV_BAD_SCALE unless lsb is finite and > 0.
 * Quantisation error inside the range: at most lsb / 2.
 */
mrqp_fw_conv mrqp_fw_quantize_fixed(double x, double lsb, unsigned bits, int32_t* code);
/** code * lsb. */
double mrqp_fw_dequantize_fixed(int32_t code, double lsb);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_SATURATE_H */
