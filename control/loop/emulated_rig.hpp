// The emulated hardware of a scene (docs/loop.md): one SimBus per bus of the hardware section,
// the controller's node on each, and the emulated firmware of every device hosted on the plant
// (PlantCia402Drive for the CiA 402 drives, PlantActuators for the MIT motors of a bus and for
// each hand board, PlantFtSensor and PlantImu for the sensors). Plant and buses advance on ONE simulated clock:
// advanceTo(t) runs the buses to t (drives receive their setpoints and SYNC, apply them to the
// plant and sample it) and then steps the plant to t, so a run is deterministic.
// Construction allocates; advanceTo and the fault injections do not.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_hand_board.hpp>
#include <mrqp/emulation/emulated_mit_motor.hpp>

#include <memory>
#include <string>
#include <vector>

#include "loop/hardware_check.hpp"
#include "loop/plant.hpp"
#include "loop/plant_actuators.hpp"
#include "loop/plant_cia402_drive.hpp"
#include "loop/plant_ft_sensor.hpp"
#include "loop/plant_imu.hpp"

namespace mrqp::loop {

class EmulatedRig {
 public:
  EmulatedRig(const ResolvedHardware& hw, const problem::MultiRobotProblem& problem, Plant& plant);
  EmulatedRig(const EmulatedRig&) = delete;
  EmulatedRig& operator=(const EmulatedRig&) = delete;

  std::size_t busCount() const noexcept { return buses_.size(); }
  /// The controller's node on bus b.
  drivers::SimNode& master(std::size_t b) noexcept { return *masters_[b]; }
  drivers::SimBus& bus(std::size_t b) noexcept { return *buses_[b]; }

  /// Runs every bus to t, then steps the plant to t (in steps of at most max_plant_step).
  void advanceTo(drivers::TimeNs t) noexcept;
  drivers::TimeNs now() const noexcept { return now_; }
  void setMaxPlantStep(drivers::TimeNs dt) noexcept { max_step_ = dt; }

  /// Drives by "ENTITY.JOINT"; nullptr when there is none.
  PlantCia402Drive* drive(const std::string& name) noexcept;
  /// The first drive, nullptr when there is none.
  PlantCia402Drive* firstDrive() noexcept { return drives_.empty() ? nullptr : drives_.front().drive.get(); }
  const std::string& driveName(const PlantCia402Drive* d) const;
  /// F/T sensors and IMUs by "ENTITY.FRAME" (nullptr: none); with an empty name the first one.
  PlantFtSensor* ftSensor(const std::string& name) noexcept;
  PlantImu* imu(const std::string& name) noexcept;
  const std::string& ftSensorName(const PlantFtSensor* s) const;
  /// The MIT motor of joint "ENTITY.JOINT", the hand board that has that joint (nullptr: none).
  emulation::EmulatedMitMotor* mitMotor(const std::string& joint) noexcept;
  emulation::EmulatedHandBoard* handBoard(const std::string& joint) noexcept;

 private:
  struct DriveSlot {
    std::string name;
    std::unique_ptr<PlantCia402Drive> drive;
  };
  Plant& plant_;
  std::vector<std::unique_ptr<drivers::SimBus>> buses_;
  std::vector<drivers::SimNode*> masters_;
  std::vector<DriveSlot> drives_;
  std::vector<std::pair<std::string, std::unique_ptr<PlantFtSensor>>> ft_;
  std::vector<std::pair<std::string, std::unique_ptr<PlantImu>>> imus_;
  std::vector<std::unique_ptr<PlantActuators<emulation::EmulatedMitMotor>>> mit_;      // one node per bus
  std::vector<int> mit_bus_;                                                           // the bus of mit_[i]
  std::vector<std::unique_ptr<PlantActuators<emulation::EmulatedHandBoard>>> boards_;  // one node per board
  std::vector<std::pair<std::string, emulation::EmulatedMitMotor*>> mit_joints_;
  std::vector<std::pair<std::string, emulation::EmulatedHandBoard*>> board_joints_;
  drivers::TimeNs now_ = 0;
  drivers::TimeNs max_step_ = 1000000;
};

}  // namespace mrqp::loop
