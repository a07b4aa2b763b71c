// The regressor model (Y_links of eq. 51) of an entity of the problem and its bodies' inertial
// parameters as the controller's model has them: a free rigid object (FreeBodyRegressorModel, the
// object's own parameters) or a generated model compiled into this library (the door). Set-up
// only: allocates and throws.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "estimation/physical_consistency.hpp"
#include "estimation/regressor_model.hpp"
#include "problem/entity.hpp"

namespace mrqp::estimation {

struct EntityRegressor {
  std::unique_ptr<RegressorModel> model;
  std::vector<InertialVector> parameters;  ///< per body of the model, about its origin
};

/// Whether makeEntityRegressor knows `model` ("rigid_object" or a generated model's name).
bool hasRegressor(const std::string& model);
/// Names of the generated models with a regressor in this build (for messages).
std::string regressorModels();

/// Throws std::invalid_argument when the model has no regressor here or the entity is not of it.
EntityRegressor makeEntityRegressor(const std::string& model, const problem::Entity& entity,
                                    const Eigen::Vector3d& gravity_world);

}  // namespace mrqp::estimation
