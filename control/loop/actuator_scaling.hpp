// The wire scaling of impedance actuators from the joints they drive (docs/loop.md, "The hardware
// section"): an MIT frame packs position and velocity into 16 and 12 bits over the motor's ranges,
// a hand board's record into i16 / i12 / i12 codes of a fixed LSB. The firmware defaults (±12.5 rad
// and ±65 rad/s over 16 and 12 bits; 1e-4 rad and 0.02 rad/s per LSB) are far too coarse for a
// small joint — a gripper finger travels 4 cm at a few cm/s — and the controller, which corrects
// its prediction by what the joint reports, would read its slow motion as standing still. So the
// ranges and LSBs come from the joint's limits (position range widened by 10 % on each side,
// velocity and torque by 50 %); a joint without a finite limit keeps the firmware's default. The
// driver and the emulated firmware are configured with the same values, as a real motor's or
// board's parameters would be. Set-up only.
#pragma once

#include <mrqp/firmware_if/hand_fd_frame.h>
#include <mrqp/firmware_if/mit_frame.h>

#include <vector>

#include "problem/entity.hpp"

namespace mrqp::loop {

/// The MIT ranges of joint `joint` (velocity index) of `entity`.
mrqp_fw_mit_ranges mitRanges(const problem::Entity& entity, int joint) noexcept;

/// The scale of a hand board driving `joints` (velocity indices) of `entity`: wide enough for
/// every one of them.
mrqp_fw_hand_scale handScale(const problem::Entity& entity, const std::vector<int>& joints) noexcept;

}  // namespace mrqp::loop
