// Regressor models of the problem's entities (see regressor_factory.hpp).
#include "estimation/regressor_factory.hpp"

#include <stdexcept>

#include "door_model.hpp"
#include "model/model_traits.hpp"
#include "problem/rigid_object.hpp"

MRQP_MODEL_TRAITS(door_model);

namespace mrqp::estimation {

namespace {

template <class M>
EntityRegressor generated(const problem::Entity& e, const Eigen::Vector3d& g_world) {
  if (e.nv() != M::nv) throw std::invalid_argument("entity '" + e.name() + "' is not of its model");
  // The generated regressor takes gravity in the model's base frame (a fixed base placed in the world).
  const Eigen::Vector3d g =
      e.floatingBase() ? g_world : Eigen::Vector3d(e.basePose().R.transpose() * g_world);
  EntityRegressor out;
  out.model = std::make_unique<GeneratedRegressorModel<M>>(g);
  typename M::ParamVector phi;
  M::params(phi);
  for (int b = 0; b < M::nbodies; ++b) out.parameters.push_back(phi.template segment<10>(10 * b));
  return out;
}

}  // namespace

bool hasRegressor(const std::string& model) { return model == "rigid_object" || model == "door"; }

std::string regressorModels() { return "rigid_object, door"; }

EntityRegressor makeEntityRegressor(const std::string& model, const problem::Entity& e,
                                    const Eigen::Vector3d& gravity_world) {
  if (model == "rigid_object") {
    const auto* obj = dynamic_cast<const problem::RigidObject*>(&e);
    if (obj == nullptr) throw std::invalid_argument("entity '" + e.name() + "' is not a rigid object");
    EntityRegressor out;
    out.model = std::make_unique<FreeBodyRegressorModel>(gravity_world);
    out.parameters.push_back(obj->inertialParameters());
    return out;
  }
  if (model == "door") return generated<door_model_model>(e, gravity_world);
  throw std::invalid_argument("no regressor for model '" + model +
                              "' in this build (models: " + regressorModels() + ")");
}

}  // namespace mrqp::estimation
