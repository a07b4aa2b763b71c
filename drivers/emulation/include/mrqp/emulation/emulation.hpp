// mrqp emulation -- umbrella header: the device firmware the plant, the tests and mrqp-drive-emu
// put on a bus (library mrqp_emulation, not part of the runtime drivers).
#pragma once

#include "mrqp/emulation/emulated_cia402_drive.hpp"
#include "mrqp/emulation/emulated_ft_sensor.hpp"
#include "mrqp/emulation/emulated_hand_board.hpp"
#include "mrqp/emulation/emulated_imu.hpp"
#include "mrqp/emulation/emulated_mit_motor.hpp"
#include "mrqp/emulation/joint_host.hpp"
#include "mrqp/emulation/sim_device_node.hpp"
