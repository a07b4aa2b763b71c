// mrqp emulation -- the former place of EmulatedCia402Drive, kept so that code written against
// mrqp::drivers::EmulatedCia402Drive compiles unchanged. The drive now lives in the emulation
// library (mrqp_emulation, <mrqp/emulation/emulated_cia402_drive.hpp>); link mrqp_emulation.
#pragma once

#include "mrqp/emulation/emulated_cia402_drive.hpp"

namespace mrqp::drivers {
using EmulatedCia402Drive = emulation::EmulatedCia402Drive;
}  // namespace mrqp::drivers
