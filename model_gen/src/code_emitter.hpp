// KinematicTree -> C++ source text of the generated model (and its JSON probe program).
#pragma once

#include <string>

#include "kinematic_tree.hpp"

namespace mrqp::gen {

struct EmittedModel {
  std::string header;  ///< NAME.hpp
  std::string source;  ///< NAME.cpp
  std::string probe;   ///< NAME_probe.cpp (empty unless requested)
};

/// `name` must be a C++ identifier; `origin` is recorded in the generated file's banner.
EmittedModel emitModel(const KinematicTree& tree, const std::string& name, const std::string& origin,
                       bool with_probe);

/// True when `name` can be a namespace (a C++ identifier that is not a keyword).
bool isValidModelName(const std::string& name);

}  // namespace mrqp::gen
