// URDF (urdfdom) -> validated KinematicTree.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "kinematic_tree.hpp"

namespace mrqp::gen {

/// A URDF that cannot become a model. The message names the element and the reason.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  bool floating_base = false;
  /// Folders searched for package://NAME/... mesh URIs (ROS_PACKAGE_PATH is searched too).
  std::vector<std::string> package_paths;
  /// Accept inertias that violate the triangle inequality (a warning instead of an error).
  bool allow_nonphysical_inertia = false;
};

/// Parses and validates a URDF file. Throws ModelError naming the element on invalid input;
/// warnings about valid but unusual input are returned in KinematicTree::warnings.
KinematicTree loadUrdfFile(const std::string& path, const LoadOptions& options);

/// Same from a URDF text; `source` names it in messages, `base_dir` resolves relative meshes.
KinematicTree loadUrdfString(const std::string& xml, const std::string& source, const std::string& base_dir,
                             const LoadOptions& options);

}  // namespace mrqp::gen
