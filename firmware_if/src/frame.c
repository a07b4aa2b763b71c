/* mrqp firmware interface -- frame envelope and CAN FD lengths. */
#include "mrqp/firmware_if/frame.h"

#include <string.h>

void mrqp_fw_frame_clear(mrqp_fw_frame* frame) {
  if (frame == NULL) {
    return;
  }
  memset(frame, 0, sizeof(*frame));
  frame->id = MRQP_FW_ID_INVALID;
}

void mrqp_fw_frame_init(mrqp_fw_frame* frame, uint32_t id, uint8_t len, uint8_t flags) {
  memset(frame, 0, sizeof(*frame));
  frame->id = id;
  frame->len = len;
  frame->flags = flags;
}

mrqp_fw_err mrqp_fw_frame_expect(const mrqp_fw_frame* frame, uint32_t id, unsigned len, int fd) {
  int is_fd;
  if (frame == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if ((frame->flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR)) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  is_fd = (frame->flags & MRQP_FW_FRAME_FD) != 0u;
  if (is_fd != (fd != 0)) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (frame->id != id) {
    return MRQP_FW_ERR_ID;
  }
  if (frame->len != len) {
    return MRQP_FW_ERR_LENGTH;
  }
  return MRQP_FW_OK;
}

int mrqp_fw_fd_len_valid(unsigned n) {
  return n <= 8u || n == 12u || n == 16u || n == 20u || n == 24u || n == 32u || n == 48u || n == 64u;
}

uint8_t mrqp_fw_fd_len_round_up(unsigned n) {
  static const uint8_t steps[] = {12u, 16u, 20u, 24u, 32u, 48u, 64u};
  unsigned i;
  if (n <= 8u) {
    return (uint8_t)n;
  }
  for (i = 0u; i < sizeof(steps); ++i) {
    if (n <= steps[i]) {
      return steps[i];
    }
  }
  return 0u;
}

uint8_t mrqp_fw_fd_dlc_to_len(uint8_t dlc) {
  static const uint8_t lens[16] = {0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 12u, 16u, 20u, 24u, 32u, 48u, 64u};
  return dlc < 16u ? lens[dlc] : (uint8_t)0u;
}

uint8_t mrqp_fw_fd_len_to_dlc(uint8_t len) {
  uint8_t dlc;
  for (dlc = 0u; dlc < 16u; ++dlc) {
    if (mrqp_fw_fd_dlc_to_len(dlc) == len) {
      return dlc;
    }
  }
  return 0xFFu;
}
