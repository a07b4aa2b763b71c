// The estimation section of a scene file resolved against the built scene, its hardware and its
// plant section (docs/estimation.md): per estimated entity what the filter estimates (its links'
// mass, mass and CoM, or all ten parameters; the (K, C, O) of spring joints), the priors, the hands
// whose F/T sensors observe it, the kinematics filter, R and Q, and whether the estimate is fed
// back into the QP's model. Plain data, read by readEstimation (estimation_yaml.hpp), run by
// EstimatorHook (estimator_hook.hpp).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "estimation/inertial_estimator.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::estimation {

/// A hand that holds the entity: its robot's F/T sensor and the contact through which it holds.
struct EstimationHandSpec {
  int robot = -1;         ///< index into the hardware section's robots (Controller::robots())
  int robot_entity = -1;  ///< the robot's entity
  int sensor = -1;        ///< index among that robot's ft_sensors
  int sensor_frame = -1;  ///< the robot frame carrying the sensor
  int contact = -1;       ///< the contact between the hand and the entity
  int object_frame = -1;  ///< the entity's frame of that contact
  int divisor = 1;        ///< the robot's cycle in loop periods (the F/T sample's rate)
  /// Mass (kg) and centre of mass (sensor frame, m) between the sensor and the object: its weight
  /// is removed from the sample.
  double tool_mass = 0.0;
  Eigen::Vector3d tool_com = Eigen::Vector3d::Zero();
  scene::Source source;
};

/// A spring joint whose (K, C, O) is estimated.
struct EstimatedSpringSpec {
  std::string joint;
  int velocity_index = -1;
  Eigen::Vector3d initial = Eigen::Vector3d::Zero();           ///< (K, C, O) the filter starts from
  Eigen::Vector3d initial_std = Eigen::Vector3d::Constant(1);  ///< its standard deviations
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();             ///< the plant's spring (the scene's)
  bool truth_known = false;
};

struct EntityEstimationSpec {
  std::string name;  ///< the entity
  int entity = -1;
  std::string model;                           ///< "rigid_object" or a generated model's name
  BodyEstimate estimate = BodyEstimate::None;  ///< for every body of a rigid object
  /// Rigid object: the filter's initial mass (kg) and CoM (object frame, m) and their deviations;
  /// the rotational inertia about the CoM is the scene's.
  double initial_mass = 0.0, initial_mass_std = 1.0;
  Eigen::Vector3d initial_com = Eigen::Vector3d::Zero();
  double initial_com_std = 0.05;
  /// The plant's true mass and CoM (the scene's rigid object; the world behind the drives).
  double true_mass = 0.0;
  Eigen::Vector3d true_com = Eigen::Vector3d::Zero();
  std::vector<EstimatedSpringSpec> springs;
  std::vector<EstimationHandSpec> hands;
  double cutoff_hz = 2.0;  ///< the kinematics and wrench filter's corner frequency
  double settle_s = 0.5;   ///< no update before the filter has settled
  /// R: the plant's F/T noise (standard deviations, N and N·m) mapped by Jᵀ, plus a floor (the
  /// standard deviation of the model's error per coordinate of μ).
  double force_noise = 0.0, torque_noise = 0.0, observation_floor = 0.05;
  double process_noise = 1e-4;  ///< Q: per update, relative to the prior's deviation
  double min_mass = 1e-3;       ///< consistency: mass floor
  bool feed_back = false;       ///< the estimate written into the QP's model of the entity
  scene::Source source;
};

struct EstimationSpec {
  bool present = false;
  std::vector<EntityEstimationSpec> entities;
};

}  // namespace mrqp::estimation
