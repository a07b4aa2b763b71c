// State of what the controller cannot measure, from the kinematics of the contacts that hold it
// (docs/loop.md, "The cycle"): a free object or a mechanism from the frames of the robots that
// hold it, the floating base of a robot from its contacts with the ground. Every established
// contact freezes the relative pose of its two frames (the world pose of its frame for a ground
// contact) when it first becomes active; each cycle the estimated coordinates of an entity are the
// least-squares fit of those poses (a few Gauss–Newton steps from the prediction, over the
// world-aligned frame Jacobians), and its velocities the least-squares fit of zero relative
// twist. A contact's free directions leave the fit; one that leaves every rotation free holds a
// point, the centre of its points, and its rows compare that point instead of the frame origin.
// Entities are estimated in order: floating bases of measured robots first, then the others,
// each from contacts whose other side is the ground or an entity already measured or estimated.
// A floating base with an IMU fuses the two (BaseAttitudeFilter, a complementary filter on SO(3)):
// at each IMU sample the base's orientation is the gyro's integration pulled towards the
// orientation the ground contacts give (the IMU's own attitude output when no ground contact
// holds), the gyro's bias is learnt, the angular velocity is the gyro's with that bias removed
// (all through the IMU frame's pose in the base, from the measured joints); the position and the
// linear velocity are then fitted to the contacts with that orientation. Set-up allocates;
// estimate() is allocation-free.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <vector>

#include <mrqp/drivers/device.hpp>

#include "loop/base_attitude_filter.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::loop {

class ContactEstimator {
 public:
  static constexpr int kMaxLinks = 8;  ///< contacts used per estimated entity

  /// `measured[e]`: entity e's joints come from its drives (a robot with hardware).
  /// `imu_frame[e]`: the frame of entity e that carries an IMU, −1 for none.
  /// `estimate_unmeasured` false: only the floating bases of measured robots are estimated.
  ContactEstimator(problem::MultiRobotProblem& problem, const std::vector<bool>& measured,
                   const std::vector<int>& imu_frame, int iterations = 2, bool estimate_unmeasured = true);

  /// The IMU sample of entity e for this cycle's estimate (orientation in the world, body rates).
  void setImu(int entity, const drivers::ImuFeedback& sample) noexcept;

  /// Records newly active contacts and estimates every entity that has contacts to fit.
  void estimate() noexcept;

  /// How entity e's unmeasured coordinates are obtained: "none", "contact kinematics".
  bool estimated(int entity) const noexcept;
  /// Largest pose residual (m or rad) of the last estimate of an entity, −1 if not estimated.
  double residual(int entity) const noexcept { return residual_[static_cast<std::size_t>(entity)]; }
  /// The gyro bias learnt for the IMU of entity e (base axes, rad/s; zero without an IMU).
  Eigen::Vector3d gyroBias(int entity) const noexcept {
    return filters_[static_cast<std::size_t>(entity)].bias();
  }

 private:
  struct Frozen {
    bool recorded = false;
    problem::Pose rel;  ///< surface frame in the other frame (the world for the ground)
  };
  struct Target {
    int entity = -1;
    int first = 0;  ///< first estimated velocity coordinate
    int count = 0;
    Eigen::MatrixXd A;  ///< stacked rows (6 kMaxLinks × count)
    Eigen::VectorXd b;
    Eigen::MatrixXd N;  ///< AᵀA (count × count)
    Eigen::VectorXd x;
    Eigen::LDLT<Eigen::MatrixXd> ldlt;
    int position_only = -1;  ///< with an IMU: the target of the position alone (in position_targets_)
  };

  problem::Pose targetPose(int contact, bool surface_side) const noexcept;
  int gather(const Target& t, std::array<int, kMaxLinks>& links,
             const std::vector<std::uint8_t>& known) const noexcept;
  // Removes the rows of contact c's free directions from block i of t's fit.
  void dropFree(int c, Target& t, int i) const noexcept;
  void fitPose(Target& t, const std::array<int, kMaxLinks>& links, int nlinks) noexcept;
  void fitVelocity(Target& t, const std::array<int, kMaxLinks>& links, int nlinks) noexcept;
  void applyIncrement(Target& t) noexcept;
  /// The IMU sample of an entity fused with its contacts (all six coordinates fitted first).
  void fuseImu(Target& t, const std::array<int, kMaxLinks>& links, int nlinks) noexcept;
  static Target makeTarget(int entity, int first, int count);

  problem::MultiRobotProblem& p_;
  std::vector<bool> measured_;
  std::vector<int> imu_frame_;
  std::vector<drivers::ImuFeedback> imu_;
  std::vector<std::uint8_t> imu_fresh_;
  int iterations_;
  std::vector<Frozen> frozen_;            // per contact slot
  std::vector<Target> targets_;           // in estimation order
  std::vector<Target> position_targets_;  // the position of a floating base with an IMU
  std::vector<BaseAttitudeFilter> filters_;
  std::vector<drivers::TimeNs> imu_time_;  // timestamp of the last fused sample, −1 before
  std::vector<std::uint8_t> known_;
  std::vector<double> residual_;
  Eigen::MatrixXd J_, Jo_;  // 6 × max nv
  Eigen::VectorXd v_save_, zero_;
};

}  // namespace mrqp::loop
