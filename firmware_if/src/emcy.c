/* mrqp firmware interface -- EMCY. */
#include "mrqp/firmware_if/emcy.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"

mrqp_fw_pack_flags mrqp_fw_emcy_pack(unsigned node, const mrqp_fw_emcy* emcy, mrqp_fw_frame* out) {
  if (out == NULL || emcy == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_EMCY_BASE + node, (uint8_t)MRQP_FW_EMCY_LEN, 0u);
  mrqp_fw_put_u16le(&out->data[0], emcy->error_code);
  out->data[2] = emcy->error_register;
  memcpy(&out->data[3], emcy->manufacturer, MRQP_FW_EMCY_MANUFACTURER_LEN);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_emcy_unpack(const mrqp_fw_frame* in, uint8_t* node, mrqp_fw_emcy* emcy) {
  uint8_t n = 0u;
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (node == NULL || emcy == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (mrqp_fw_cob_decode(in->id, &n) != MRQP_FW_COB_KIND_EMCY) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len != MRQP_FW_EMCY_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  if ((in->data[2] & MRQP_FW_ERRREG_RESERVED) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  *node = n;
  emcy->error_code = mrqp_fw_get_u16le(&in->data[0]);
  emcy->error_register = in->data[2];
  memcpy(emcy->manufacturer, &in->data[3], MRQP_FW_EMCY_MANUFACTURER_LEN);
  return MRQP_FW_OK;
}

const char* mrqp_fw_emcy_code_str(uint16_t code) {
  switch (code) {
    case MRQP_FW_EMCY_NO_ERROR:
      return "error reset or no error";
    case MRQP_FW_EMCY_CONTINUOUS_OVER_CURRENT:
      return "continuous over-current";
    case MRQP_FW_EMCY_DC_LINK_OVER_VOLTAGE:
      return "DC link over-voltage";
    case MRQP_FW_EMCY_DC_LINK_UNDER_VOLTAGE:
      return "DC link under-voltage";
    case MRQP_FW_EMCY_DEVICE_OVER_TEMPERATURE:
      return "excess temperature device";
    case MRQP_FW_EMCY_SENSOR:
      return "sensor";
    case MRQP_FW_EMCY_INCREMENTAL_SENSOR_1:
      return "incremental sensor 1 fault";
    case MRQP_FW_EMCY_COMMUNICATION:
      return "communication";
    case MRQP_FW_EMCY_CAN_OVERRUN:
      return "CAN overrun (objects lost)";
    case MRQP_FW_EMCY_CAN_ERROR_PASSIVE:
      return "CAN in error passive mode";
    case MRQP_FW_EMCY_HEARTBEAT_ERROR:
      return "life guard error or heartbeat error";
    case MRQP_FW_EMCY_BUS_OFF_RECOVERED:
      return "recovered from bus off";
    case MRQP_FW_EMCY_PDO_LENGTH_ERROR:
      return "PDO not processed due to length error";
    case MRQP_FW_EMCY_PDO_LENGTH_EXCEEDED:
      return "PDO length exceeded";
    case MRQP_FW_EMCY_RPDO_TIMEOUT:
      return "RPDO timeout";
    case MRQP_FW_EMCY_FOLLOWING_ERROR:
      return "following error";
    case MRQP_FW_EMCY_DEVICE_SPECIFIC:
      return "device specific";
    default:
      break;
  }
  switch (code >> 12) {
    case 0x1u:
      return "generic error";
    case 0x2u:
      return "current";
    case 0x3u:
      return "voltage";
    case 0x4u:
      return "temperature";
    case 0x5u:
      return "device hardware";
    case 0x6u:
      return "device software";
    case 0x7u:
      return "additional modules";
    case 0x8u:
      return "monitoring";
    case 0x9u:
      return "external error";
    case 0xFu:
      return (code >> 8) == 0xFFu ? "device specific" : "additional functions";
    default:
      break;
  }
  return "unknown emergency code";
}
