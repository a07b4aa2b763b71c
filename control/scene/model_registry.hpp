// Models a scene file may name: a name → factory table. The generated models compiled into a
// program register themselves here (builtin_models.hpp for the ones mrqp ships with).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "problem/entity.hpp"

namespace mrqp::scene {

class ModelRegistry {
 public:
  using Factory = std::function<std::unique_ptr<problem::Entity>(const std::string& entity_name)>;

  void add(const std::string& model, Factory f) { factories_[model] = std::move(f); }
  bool has(const std::string& model) const { return factories_.count(model) != 0; }
  /// nullptr when unknown.
  std::unique_ptr<problem::Entity> make(const std::string& model, const std::string& name) const {
    auto it = factories_.find(model);
    return it == factories_.end() ? nullptr : it->second(name);
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& kv : factories_) out.push_back(kv.first);
    return out;
  }

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace mrqp::scene
