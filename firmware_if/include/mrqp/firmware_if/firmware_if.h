/* mrqp firmware interface -- umbrella header: the whole wire contract. */
#ifndef MRQP_FIRMWARE_IF_FIRMWARE_IF_H
#define MRQP_FIRMWARE_IF_FIRMWARE_IF_H

#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/arm_scale.h"
#include "mrqp/firmware_if/bus_timing.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/cia402.h"
#include "mrqp/firmware_if/crc.h"
#include "mrqp/firmware_if/emcy.h"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/ft_sensor.h"
#include "mrqp/firmware_if/hand_fd_frame.h"
#include "mrqp/firmware_if/imu.h"
#include "mrqp/firmware_if/mit_frame.h"
#include "mrqp/firmware_if/nmt.h"
#include "mrqp/firmware_if/objects.h"
#include "mrqp/firmware_if/saturate.h"
#include "mrqp/firmware_if/sdo.h"
#include "mrqp/firmware_if/sdo_client.h"
#include "mrqp/firmware_if/status.h"
#include "mrqp/firmware_if/sync.h"

#endif /* MRQP_FIRMWARE_IF_FIRMWARE_IF_H */
