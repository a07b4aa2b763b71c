/* Entry points of c_usage.c, callable from the C++ tests. */
#ifndef MRQP_TESTS_FIRMWARE_IF_C_USAGE_H
#define MRQP_TESTS_FIRMWARE_IF_C_USAGE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Writes the MIT enable frame for motor 5; returns its length (8) or -1. */
int mrqp_fw_c_enable_frame(uint8_t out[8], uint32_t* id);
/** Enables an emulated CiA 402 drive through packed PDOs; returns the cycles needed or -1. */
int mrqp_fw_c_emulated_drive_enable(void);

#ifdef __cplusplus
}
#endif

#endif
