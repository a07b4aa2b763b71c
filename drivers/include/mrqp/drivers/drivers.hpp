// mrqp drivers -- umbrella header.
#pragma once

#include "mrqp/drivers/arm_driver.hpp"
#include "mrqp/drivers/budget_table.hpp"
#include "mrqp/drivers/bus.hpp"
#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/bus_health.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/emulated_cia402_drive.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/fd_hand_driver.hpp"
#include "mrqp/drivers/ft_sensor_driver.hpp"
#include "mrqp/drivers/mit_hand_driver.hpp"
#include "mrqp/drivers/router_attachment.hpp"
#include "mrqp/drivers/setpoint.hpp"
#include "mrqp/drivers/sim_bus.hpp"
#include "mrqp/drivers/socketcan_bus.hpp"
#include "mrqp/drivers/time.hpp"
