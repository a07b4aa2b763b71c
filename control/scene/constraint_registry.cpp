// The registry of constraint kinds: ONE line per kind (docs/adding-a-task.md). The order is the
// order in which the top-level lists are read (and their errors found) and built.
#include "scene/constraint_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

// Each kind lives in constraint_kinds/<kind>.cpp.
ConstraintKindEntry comDamperKind();
ConstraintKindEntry jointInequalityKind();
ConstraintKindEntry collisionKind();

const std::vector<ConstraintKindEntry>& constraintKinds() {
  static const std::vector<ConstraintKindEntry> kinds = {
      comDamperKind(),
      jointInequalityKind(),
      collisionKind(),
  };
  return kinds;
}

void readDamperGains(const Map& m, double* interaction, double* security, double* damping) {
  *security = m.number("security", Bound::NonNegative, *security);
  *interaction = m.number("interaction", Bound::Any, *interaction);
  if (!(*interaction > *security)) {
    const Reader& r = m.reader();
    if (const YAML::Node* n = m.find("interaction")) {
      r.fail(*n, m.at("interaction"),
             "expected a number > security (" + formatNumber(*security) + "), got " + describe(*n));
    }
    r.fail(m.require("security"), m.at("security"),
           "expected a number < interaction (" + formatNumber(*interaction) + "), got " +
               describe(m.require("security")));
  }
  *damping = m.number("damping", Bound::Positive, *damping);
}

}  // namespace mrqp::scene
