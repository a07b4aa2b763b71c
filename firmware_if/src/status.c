/* mrqp firmware interface -- error names. */
#include "mrqp/firmware_if/status.h"

const char* mrqp_fw_err_str(mrqp_fw_err err) {
  switch (err) {
    case MRQP_FW_OK:
      return "ok";
    case MRQP_FW_ERR_NULL:
      return "null pointer argument";
    case MRQP_FW_ERR_ID:
      return "unexpected CAN identifier";
    case MRQP_FW_ERR_FORMAT:
      return "wrong frame format (classic/FD/extended/remote) or non-zero reserved bits";
    case MRQP_FW_ERR_LENGTH:
      return "wrong data length";
    case MRQP_FW_ERR_CRC:
      return "CRC mismatch";
    case MRQP_FW_ERR_RANGE:
      return "field value out of range";
    case MRQP_FW_ERR_COMMAND:
      return "unknown or unsupported command or state code";
    case MRQP_FW_ERR_VERSION:
      return "unsupported protocol version";
    case MRQP_FW_ERR_CONFIG:
      return "invalid scaling or range configuration";
    case MRQP_FW_ERR_TORN:
      return "torn sample: sequence or status differ between its frames";
  }
  return "unknown error code";
}
