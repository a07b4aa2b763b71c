/* mrqp firmware interface -- arm drive units <-> SI. */
#include "mrqp/firmware_if/arm_scale.h"

#include <stddef.h>

#include "mrqp/firmware_if/saturate.h"

#define MRQP_FW_TWO_PI 6.283185307179586476925286766559

int mrqp_fw_arm_scale_valid(const mrqp_fw_arm_scale* scale) {
  return scale != NULL && scale->increments_per_rev > 0u && scale->rated_torque_mNm > 0u;
}

static mrqp_fw_conv to_i32(double x, int32_t* out) {
  int64_t v = 0;
  mrqp_fw_conv r = mrqp_fw_quantize_int(x, INT32_MIN, INT32_MAX, &v);
  if (r == MRQP_FW_CONV_OK || r == MRQP_FW_CONV_SAT_LOW || r == MRQP_FW_CONV_SAT_HIGH) {
    *out = (int32_t)v;
  }
  return r;
}

mrqp_fw_conv mrqp_fw_arm_position_to_inc(const mrqp_fw_arm_scale* scale, double rad, int32_t* inc) {
  if (!mrqp_fw_arm_scale_valid(scale) || inc == NULL) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  return to_i32(rad * ((double)scale->increments_per_rev / MRQP_FW_TWO_PI), inc);
}

mrqp_fw_conv mrqp_fw_arm_position_from_inc(const mrqp_fw_arm_scale* scale, int32_t inc, double* rad) {
  if (!mrqp_fw_arm_scale_valid(scale) || rad == NULL) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  *rad = (double)inc * (MRQP_FW_TWO_PI / (double)scale->increments_per_rev);
  return MRQP_FW_CONV_OK;
}

mrqp_fw_conv mrqp_fw_arm_velocity_to_inc(const mrqp_fw_arm_scale* scale, double rad_s, int32_t* inc_s) {
  return mrqp_fw_arm_position_to_inc(scale, rad_s, inc_s); /* same factor, per second */
}

mrqp_fw_conv mrqp_fw_arm_velocity_from_inc(const mrqp_fw_arm_scale* scale, int32_t inc_s, double* rad_s) {
  return mrqp_fw_arm_position_from_inc(scale, inc_s, rad_s);
}

mrqp_fw_conv mrqp_fw_arm_torque_to_permille(const mrqp_fw_arm_scale* scale, double nm, int16_t* permille) {
  int64_t v = 0;
  mrqp_fw_conv r;
  if (!mrqp_fw_arm_scale_valid(scale) || permille == NULL) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  /* per mille = N m / (rated mN m / 1000 N m) * 1000 */
  r = mrqp_fw_quantize_int(nm * (1.0e6 / (double)scale->rated_torque_mNm), INT16_MIN, INT16_MAX, &v);
  if (r == MRQP_FW_CONV_OK || r == MRQP_FW_CONV_SAT_LOW || r == MRQP_FW_CONV_SAT_HIGH) {
    *permille = (int16_t)v;
  }
  return r;
}

mrqp_fw_conv mrqp_fw_arm_torque_from_permille(const mrqp_fw_arm_scale* scale, int16_t permille, double* nm) {
  if (!mrqp_fw_arm_scale_valid(scale) || nm == NULL) {
    return MRQP_FW_CONV_BAD_SCALE;
  }
  *nm = (double)permille * ((double)scale->rated_torque_mNm / 1.0e6);
  return MRQP_FW_CONV_OK;
}
