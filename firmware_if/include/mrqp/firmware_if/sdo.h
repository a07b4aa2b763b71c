/*
 * mrqp firmware interface -- CANopen SDO frames (CiA 301): expedited and segmented transfer.
 *
 * Client (master) -> server (device): COB-ID 0x600 + node. Server -> client: 0x580 + node.
 * Every SDO frame has DLC 8. Byte 0 is the command specifier (cs); for initiate and abort frames
 * bytes 1-2 are the index (little-endian) and byte 3 the sub-index ("multiplexer").
 *
 *   initiate download request   ccs=1  001 0 nn e s  idx sub d0..d3   (expedited: e=1, s=1, 4-nn bytes)
 *   initiate download response  scs=3  0110 0000     idx sub 0 0 0 0
 *   initiate upload request     ccs=2  0100 0000     idx sub 0 0 0 0
 *   initiate upload response    scs=2  010 0 nn e s  idx sub d0..d3   (segmented: e=0, s=1, size u32)
 *   download segment request    ccs=0  000 t nnn c   7 data bytes (7-nnn valid, c = last)
 *   download segment response   scs=1  001 t 0000    0 x 7
 *   upload segment request      ccs=3  011 t 0000    0 x 7
 *   upload segment response     scs=0  000 t nnn c   7 data bytes
 *   abort transfer              cs=4   1000 0000     idx sub abort-code u32
 * Expedited command bytes: download 0x2F/0x2B/0x27/0x23 and upload response 0x4F/0x4B/0x47/0x43
 * for 1/2/3/4 bytes. Block transfer (cs 5, 6) is not part of this contract.
 */
#ifndef MRQP_FIRMWARE_IF_SDO_H
#define MRQP_FIRMWARE_IF_SDO_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_SDO_LEN 8u
#define MRQP_FW_SDO_SEGMENT_DATA 7u

/* Command specifier values (top three bits of byte 0). */
#define MRQP_FW_SDO_CCS_DOWNLOAD_SEGMENT 0u
#define MRQP_FW_SDO_CCS_INITIATE_DOWNLOAD 1u
#define MRQP_FW_SDO_CCS_INITIATE_UPLOAD 2u
#define MRQP_FW_SDO_CCS_UPLOAD_SEGMENT 3u
#define MRQP_FW_SDO_SCS_UPLOAD_SEGMENT 0u
#define MRQP_FW_SDO_SCS_DOWNLOAD_SEGMENT 1u
#define MRQP_FW_SDO_SCS_INITIATE_UPLOAD 2u
#define MRQP_FW_SDO_SCS_INITIATE_DOWNLOAD 3u
#define MRQP_FW_SDO_CS_ABORT 4u

/* SDO abort codes (CiA 301). */
#define MRQP_FW_SDO_ABORT_TOGGLE 0x05030000u
#define MRQP_FW_SDO_ABORT_TIMEOUT 0x05040000u
#define MRQP_FW_SDO_ABORT_COMMAND 0x05040001u
#define MRQP_FW_SDO_ABORT_BLOCK_SIZE 0x05040002u
#define MRQP_FW_SDO_ABORT_SEQUENCE 0x05040003u
#define MRQP_FW_SDO_ABORT_CRC 0x05040004u
#define MRQP_FW_SDO_ABORT_OUT_OF_MEMORY 0x05040005u
#define MRQP_FW_SDO_ABORT_UNSUPPORTED_ACCESS 0x06010000u
#define MRQP_FW_SDO_ABORT_WRITE_ONLY 0x06010001u
#define MRQP_FW_SDO_ABORT_READ_ONLY 0x06010002u
#define MRQP_FW_SDO_ABORT_NO_OBJECT 0x06020000u
#define MRQP_FW_SDO_ABORT_NOT_MAPPABLE 0x06040041u
#define MRQP_FW_SDO_ABORT_PDO_LENGTH 0x06040042u
#define MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE 0x06040043u
#define MRQP_FW_SDO_ABORT_INTERNAL_INCOMPATIBLE 0x06040047u
#define MRQP_FW_SDO_ABORT_HARDWARE 0x06060000u
#define MRQP_FW_SDO_ABORT_TYPE_LENGTH 0x06070010u
#define MRQP_FW_SDO_ABORT_TYPE_LENGTH_HIGH 0x06070012u
#define MRQP_FW_SDO_ABORT_TYPE_LENGTH_LOW 0x06070013u
#define MRQP_FW_SDO_ABORT_NO_SUBINDEX 0x06090011u
#define MRQP_FW_SDO_ABORT_INVALID_VALUE 0x06090030u
#define MRQP_FW_SDO_ABORT_VALUE_HIGH 0x06090031u
#define MRQP_FW_SDO_ABORT_VALUE_LOW 0x06090032u
#define MRQP_FW_SDO_ABORT_MAX_LESS_MIN 0x06090036u
#define MRQP_FW_SDO_ABORT_NO_RESOURCE 0x060A0023u
#define MRQP_FW_SDO_ABORT_GENERAL 0x08000000u
#define MRQP_FW_SDO_ABORT_STORE 0x08000020u
#define MRQP_FW_SDO_ABORT_STORE_LOCAL 0x08000021u
#define MRQP_FW_SDO_ABORT_STORE_STATE 0x08000022u
#define MRQP_FW_SDO_ABORT_NO_DICTIONARY 0x08000023u
#define MRQP_FW_SDO_ABORT_NO_DATA 0x08000024u

/** The name of an abort code as worded by CiA 301; "unknown SDO abort code" otherwise. */
const char* mrqp_fw_sdo_abort_str(uint32_t code);

/** What an SDO frame is. */
typedef enum mrqp_fw_sdo_kind {
  MRQP_FW_SDO_DOWNLOAD_INIT_REQ = 0, /**< client: write (expedited, or segmented with size) */
  MRQP_FW_SDO_DOWNLOAD_INIT_RESP,    /**< server: write accepted */
  MRQP_FW_SDO_UPLOAD_INIT_REQ,       /**< client: read */
  MRQP_FW_SDO_UPLOAD_INIT_RESP,      /**< server: expedited data, or segmented with size */
  MRQP_FW_SDO_DOWNLOAD_SEG_REQ,      /**< client: one segment of a write */
  MRQP_FW_SDO_DOWNLOAD_SEG_RESP,     /**< server: segment acknowledged */
  MRQP_FW_SDO_UPLOAD_SEG_REQ,        /**< client: next segment please */
  MRQP_FW_SDO_UPLOAD_SEG_RESP,       /**< server: one segment of a read */
  MRQP_FW_SDO_ABORT                  /**< either side */
} mrqp_fw_sdo_kind;

/** A decoded SDO frame. Fields not used by `kind` are zero. */
typedef struct mrqp_fw_sdo_msg {
  mrqp_fw_sdo_kind kind;
  uint8_t node;           /**< from the COB-ID */
  uint8_t from_server;    /**< 1 for 0x580 + node, 0 for 0x600 + node */
  uint16_t index;         /**< initiate and abort frames */
  uint8_t subindex;       /**< initiate and abort frames */
  uint8_t expedited;      /**< initiate download req / upload resp: data in the frame */
  uint8_t size_indicated; /**< initiate: size (expedited) or total size (segmented) is given */
  uint8_t toggle;         /**< segment frames: toggle bit */
  uint8_t last;           /**< segment request/response with data: c bit (no more segments) */
  uint8_t n;           /**< number of valid bytes in data: expedited 1..4 (4 if unspecified), segment 0..7 */
  uint32_t size;       /**< segmented initiate: total size in bytes */
  uint32_t abort_code; /**< abort */
  uint8_t data[7];     /**< expedited or segment data */
} mrqp_fw_sdo_msg;

/* ---- expedited transfer ---- */

/** Client: expedited write of n = 1..4 bytes. ERR_ARG for invalid node, n or NULL data. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_req(unsigned node, uint16_t index, uint8_t subindex,
                                                 const uint8_t* data, unsigned n, mrqp_fw_frame* out);
/** Server: write confirmed. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_resp(unsigned node, uint16_t index, uint8_t subindex,
                                                  mrqp_fw_frame* out);
/** Client: read request. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_req(unsigned node, uint16_t index, uint8_t subindex,
                                               mrqp_fw_frame* out);
/** Server: expedited read response with n = 1..4 bytes. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_resp(unsigned node, uint16_t index, uint8_t subindex,
                                                const uint8_t* data, unsigned n, mrqp_fw_frame* out);
/** Abort from the client (from_server 0, COB 0x600 + node) or the server (0x580 + node). */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_abort(unsigned node, int from_server, uint16_t index, uint8_t subindex,
                                          uint32_t abort_code, mrqp_fw_frame* out);

/** Little-endian values for expedited data (n = 1, 2 or 4). */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_u32(unsigned node, uint16_t index, uint8_t subindex,
                                                 uint32_t value, unsigned n, mrqp_fw_frame* out);

/* ---- segmented transfer ---- */

/** Client: initiate a segmented write of `size` bytes (size indicated). */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_init_segmented(unsigned node, uint16_t index, uint8_t subindex,
                                                            uint32_t size, mrqp_fw_frame* out);
/** Server: initiate a segmented read response announcing `size` bytes. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_resp_segmented(unsigned node, uint16_t index, uint8_t subindex,
                                                          uint32_t size, mrqp_fw_frame* out);
/** Client (download segment request) or server (upload segment response): n = 0..7 bytes. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_segment(unsigned node, int from_server, unsigned toggle,
                                            const uint8_t* data, unsigned n, int last, mrqp_fw_frame* out);
/** Server: download segment acknowledged. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_seg_resp(unsigned node, unsigned toggle, mrqp_fw_frame* out);
/** Client: upload segment request. */
mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_seg_req(unsigned node, unsigned toggle, mrqp_fw_frame* out);

/**
 * Decodes any SDO frame. Validates: classic, COB-ID 0x581..0x5FF or 0x601..0x67F (ERR_ID),
 * DLC 8 (ERR_LENGTH), command specifier known for the direction (ERR_COMMAND; block transfer
 * cs 5/6 is not supported). Bits and bytes CiA 301 marks "not used" are ignored, as third-party
 * drives do not all clear them. Expedited without size indication yields n = 4; a segmented
 * initiate without size indication is accepted with size_indicated 0.
 */
mrqp_fw_err mrqp_fw_sdo_unpack(const mrqp_fw_frame* in, mrqp_fw_sdo_msg* msg);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_SDO_H */
