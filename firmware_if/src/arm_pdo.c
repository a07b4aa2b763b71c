/* mrqp firmware interface -- arm drive default PDO mapping. */
#include "mrqp/firmware_if/arm_pdo.h"

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/objects.h"

unsigned mrqp_fw_arm_pdo_mapping(mrqp_fw_arm_pdo pdo, uint32_t entries[4]) {
  switch (pdo) {
    case MRQP_FW_ARM_RPDO1:
      entries[0] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_CONTROLWORD, 0u, 16u);
      entries[1] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_TARGET_POSITION, 0u, 32u);
      entries[2] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_TARGET_TORQUE, 0u, 16u);
      return 3u;
    case MRQP_FW_ARM_TPDO1:
      entries[0] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_STATUSWORD, 0u, 16u);
      entries[1] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_POSITION_ACTUAL, 0u, 32u);
      entries[2] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_TORQUE_ACTUAL, 0u, 16u);
      return 3u;
    case MRQP_FW_ARM_TPDO2:
      entries[0] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_VELOCITY_ACTUAL, 0u, 32u);
      entries[1] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_ERROR_CODE, 0u, 16u);
      entries[2] = MRQP_FW_PDO_MAP_ENTRY(MRQP_FW_OBJ_MODES_OF_OPERATION_DISPLAY, 0u, 8u);
      return 3u;
  }
  return 0u;
}

/* Checks the envelope of a PDO frame of `node` at COB base `base` and length `len`. */
static mrqp_fw_err expect_pdo(const mrqp_fw_frame* in, unsigned node, uint32_t base, unsigned len) {
  if (in == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_node_valid(node)) {
    return MRQP_FW_ERR_ID;
  }
  return mrqp_fw_frame_expect(in, base + node, len, 0);
}

mrqp_fw_pack_flags mrqp_fw_arm_pack_rpdo1(unsigned node, const mrqp_fw_arm_rpdo1* pdo, mrqp_fw_frame* out) {
  if (out == NULL || pdo == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_RPDO1_BASE + node, (uint8_t)MRQP_FW_ARM_RPDO1_LEN, 0u);
  mrqp_fw_put_u16le(&out->data[0], pdo->controlword);
  mrqp_fw_put_u32le(&out->data[2], (uint32_t)pdo->target_position);
  mrqp_fw_put_u16le(&out->data[6], (uint16_t)pdo->target_torque);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_arm_unpack_rpdo1(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_rpdo1* pdo) {
  mrqp_fw_err e = expect_pdo(in, node, MRQP_FW_COB_RPDO1_BASE, MRQP_FW_ARM_RPDO1_LEN);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (pdo == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  pdo->controlword = mrqp_fw_get_u16le(&in->data[0]);
  pdo->target_position = mrqp_fw_u32_to_i32(mrqp_fw_get_u32le(&in->data[2]));
  pdo->target_torque = mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[6]));
  return MRQP_FW_OK;
}

mrqp_fw_pack_flags mrqp_fw_arm_pack_tpdo1(unsigned node, const mrqp_fw_arm_tpdo1* pdo, mrqp_fw_frame* out) {
  if (out == NULL || pdo == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_TPDO1_BASE + node, (uint8_t)MRQP_FW_ARM_TPDO1_LEN, 0u);
  mrqp_fw_put_u16le(&out->data[0], pdo->statusword);
  mrqp_fw_put_u32le(&out->data[2], (uint32_t)pdo->position_actual);
  mrqp_fw_put_u16le(&out->data[6], (uint16_t)pdo->torque_actual);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_arm_unpack_tpdo1(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_tpdo1* pdo) {
  mrqp_fw_err e = expect_pdo(in, node, MRQP_FW_COB_TPDO1_BASE, MRQP_FW_ARM_TPDO1_LEN);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (pdo == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  pdo->statusword = mrqp_fw_get_u16le(&in->data[0]);
  pdo->position_actual = mrqp_fw_u32_to_i32(mrqp_fw_get_u32le(&in->data[2]));
  pdo->torque_actual = mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[6]));
  return MRQP_FW_OK;
}

mrqp_fw_pack_flags mrqp_fw_arm_pack_tpdo2(unsigned node, const mrqp_fw_arm_tpdo2* pdo, mrqp_fw_frame* out) {
  if (out == NULL || pdo == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_TPDO2_BASE + node, (uint8_t)MRQP_FW_ARM_TPDO2_LEN, 0u);
  mrqp_fw_put_u32le(&out->data[0], (uint32_t)pdo->velocity_actual);
  mrqp_fw_put_u16le(&out->data[4], pdo->error_code);
  out->data[6] = (uint8_t)pdo->mode_display;
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_arm_unpack_tpdo2(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_tpdo2* pdo) {
  mrqp_fw_err e = expect_pdo(in, node, MRQP_FW_COB_TPDO2_BASE, MRQP_FW_ARM_TPDO2_LEN);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (pdo == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  pdo->velocity_actual = mrqp_fw_u32_to_i32(mrqp_fw_get_u32le(&in->data[0]));
  pdo->error_code = mrqp_fw_get_u16le(&in->data[4]);
  pdo->mode_display = (int8_t)mrqp_fw_sign_extend(in->data[6], 8u);
  return MRQP_FW_OK;
}

mrqp_fw_pack_flags mrqp_fw_arm_pack_rpdo1_si(const mrqp_fw_arm_scale* scale, unsigned node,
                                             uint16_t controlword, double position_rad, double torque_nm,
                                             mrqp_fw_frame* out) {
  mrqp_fw_arm_rpdo1 pdo;
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  mrqp_fw_conv rp;
  mrqp_fw_conv rt;
  if (out == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_arm_scale_valid(scale)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  pdo.controlword = controlword;
  pdo.target_position = 0;
  pdo.target_torque = 0;
  rp = mrqp_fw_arm_position_to_inc(scale, position_rad, &pdo.target_position);
  rt = mrqp_fw_arm_torque_to_permille(scale, torque_nm, &pdo.target_torque);
  if (rp == MRQP_FW_CONV_NAN || rt == MRQP_FW_CONV_NAN) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_NAN);
  }
  if (rp != MRQP_FW_CONV_OK) {
    flags |= MRQP_FW_ARM_SAT_POSITION;
  }
  if (rt != MRQP_FW_CONV_OK) {
    flags |= MRQP_FW_ARM_SAT_TORQUE;
  }
  (void)mrqp_fw_arm_pack_rpdo1(node, &pdo, out);
  return flags;
}
