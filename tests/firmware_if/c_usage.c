/* A plain C99 user of the library, as drive firmware would be (compiled as ISO C99). */
#include <mrqp/firmware_if/firmware_if.h>

#include "c_usage.h"

int mrqp_fw_c_enable_frame(uint8_t out[8], uint32_t* id) {
  mrqp_fw_frame f;
  unsigned i;
  if (mrqp_fw_pack_failed(mrqp_fw_mit_pack_special(5u, MRQP_FW_MIT_KIND_ENABLE, &f))) {
    return -1;
  }
  for (i = 0u; i < 8u; ++i) {
    out[i] = f.data[i];
  }
  *id = f.id;
  return (int)f.len;
}

int mrqp_fw_c_emulated_drive_enable(void) {
  /* A drive powering up, a master enabling it over RPDO1/TPDO1 frames. */
  const mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  mrqp_fw_cia402_state drive = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
  uint16_t prev_cw = 0u;
  int cycles = 0;
  drive = mrqp_fw_cia402_drive_event(drive, MRQP_FW_CIA402_EV_INIT_COMPLETE, NULL);
  while (cycles < 10) {
    mrqp_fw_frame tx;
    mrqp_fw_frame rx;
    mrqp_fw_arm_tpdo1 fb;
    mrqp_fw_arm_rpdo1 cmd;
    mrqp_fw_arm_tpdo1 seen;
    uint16_t cw;
    fb.statusword = mrqp_fw_cia402_statusword(drive, MRQP_FW_SW_REMOTE);
    fb.position_actual = 0;
    fb.torque_actual = 0;
    if (mrqp_fw_arm_pack_tpdo1(1u, &fb, &tx) != MRQP_FW_PACK_OK ||
        mrqp_fw_arm_unpack_tpdo1(&tx, 1u, &seen) != MRQP_FW_OK) {
      return -1;
    }
    if (mrqp_fw_cia402_decode_statusword(seen.statusword) == MRQP_FW_CIA402_OPERATION_ENABLED) {
      return cycles;
    }
    cw = mrqp_fw_cia402_master_controlword(mrqp_fw_cia402_decode_statusword(seen.statusword),
                                           MRQP_FW_CIA402_OPERATION_ENABLED, prev_cw);
    if (mrqp_fw_arm_pack_rpdo1_si(&scale, 1u, cw, 0.0, 0.0, &rx) != MRQP_FW_PACK_OK ||
        mrqp_fw_arm_unpack_rpdo1(&rx, 1u, &cmd) != MRQP_FW_OK) {
      return -1;
    }
    drive = mrqp_fw_cia402_drive_next(drive, cmd.controlword, prev_cw, NULL);
    prev_cw = cmd.controlword;
    ++cycles;
  }
  return -1;
}
