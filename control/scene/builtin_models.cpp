#include "scene/builtin_models.hpp"

#include "door_model.hpp"
#include "jvrc1_model.hpp"
#include "panda_model.hpp"
#include "pen_model.hpp"
#include "problem/model_entity.hpp"
#include "shadow_hand_model.hpp"

MRQP_MODEL_TRAITS(panda_model);
MRQP_MODEL_TRAITS(jvrc1_model);
MRQP_MODEL_TRAITS(door_model);
MRQP_MODEL_TRAITS(shadow_hand_model);
MRQP_MODEL_TRAITS(pen_model);

namespace mrqp::scene {

namespace {
template <class M>
ModelRegistry::Factory factory() {
  return [](const std::string& name) -> std::unique_ptr<problem::Entity> {
    return std::make_unique<problem::ModelEntity<M>>(name);
  };
}
}  // namespace

void addBuiltinModels(ModelRegistry& registry) {
  registry.add("panda", factory<panda_model_model>());
  registry.add("jvrc1", factory<jvrc1_model_model>());
  registry.add("door", factory<door_model_model>());
  registry.add("shadow_hand", factory<shadow_hand_model_model>());
  registry.add("pen", factory<pen_model_model>());
}

}  // namespace mrqp::scene
