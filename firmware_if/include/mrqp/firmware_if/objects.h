/*
 * mrqp firmware interface -- object dictionary indices used by this contract
 * (CiA 301 communication profile, CiA 402 drive profile).
 */
#ifndef MRQP_FIRMWARE_IF_OBJECTS_H
#define MRQP_FIRMWARE_IF_OBJECTS_H

#ifdef __cplusplus
extern "C" {
#endif

/* ---- CiA 301 communication profile ---- */
#define MRQP_FW_OBJ_DEVICE_TYPE 0x1000u        /**< u32 */
#define MRQP_FW_OBJ_ERROR_REGISTER 0x1001u     /**< u8 */
#define MRQP_FW_OBJ_COB_ID_SYNC 0x1005u        /**< u32 */
#define MRQP_FW_OBJ_COMM_CYCLE_PERIOD 0x1006u  /**< u32, microseconds */
#define MRQP_FW_OBJ_DEVICE_NAME 0x1008u        /**< visible string (segmented SDO) */
#define MRQP_FW_OBJ_CONSUMER_HEARTBEAT 0x1016u /**< u32 array: node << 16 | time ms */
#define MRQP_FW_OBJ_PRODUCER_HEARTBEAT 0x1017u /**< u16, milliseconds */
#define MRQP_FW_OBJ_IDENTITY 0x1018u           /**< record */
#define MRQP_FW_OBJ_RPDO_COMM_BASE 0x1400u     /**< + (n - 1): RPDO n communication parameter */
#define MRQP_FW_OBJ_RPDO_MAP_BASE 0x1600u      /**< + (n - 1): RPDO n mapping */
#define MRQP_FW_OBJ_TPDO_COMM_BASE 0x1800u     /**< + (n - 1): TPDO n communication parameter */
#define MRQP_FW_OBJ_TPDO_MAP_BASE 0x1A00u      /**< + (n - 1): TPDO n mapping */

/* ---- CiA 402 drive profile ---- */
#define MRQP_FW_OBJ_ERROR_CODE 0x603Fu                  /**< u16, last EMCY error code */
#define MRQP_FW_OBJ_CONTROLWORD 0x6040u                 /**< u16 */
#define MRQP_FW_OBJ_STATUSWORD 0x6041u                  /**< u16 */
#define MRQP_FW_OBJ_QUICK_STOP_OPTION 0x605Au           /**< i16 */
#define MRQP_FW_OBJ_MODES_OF_OPERATION 0x6060u          /**< i8 */
#define MRQP_FW_OBJ_MODES_OF_OPERATION_DISPLAY 0x6061u  /**< i8 */
#define MRQP_FW_OBJ_POSITION_ACTUAL 0x6064u             /**< i32, increments */
#define MRQP_FW_OBJ_VELOCITY_ACTUAL 0x606Cu             /**< i32, increments / s */
#define MRQP_FW_OBJ_TARGET_TORQUE 0x6071u               /**< i16, per mille of rated torque */
#define MRQP_FW_OBJ_MAX_TORQUE 0x6072u                  /**< u16, per mille of rated torque */
#define MRQP_FW_OBJ_MOTOR_RATED_TORQUE 0x6076u          /**< u32, mN m */
#define MRQP_FW_OBJ_TORQUE_ACTUAL 0x6077u               /**< i16, per mille of rated torque */
#define MRQP_FW_OBJ_TARGET_POSITION 0x607Au             /**< i32, increments */
#define MRQP_FW_OBJ_POSITION_ENCODER_RESOLUTION 0x608Fu /**< u32 record: increments / revolutions */
#define MRQP_FW_OBJ_TORQUE_OFFSET 0x60B2u               /**< i16, per mille (not mapped by default) */
#define MRQP_FW_OBJ_SUPPORTED_DRIVE_MODES 0x6502u       /**< u32 */

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_OBJECTS_H */
