// Scene list `com_dampers` (problem::ComDamper): one CoM support-region damper per entity,
// {entity, interaction, security, damping}; 16 inequality rows each.
#include "problem/constraints/com_damper.hpp"
#include "scene/constraint_kind.hpp"
#include "scene/scene_builder.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

std::string read(const Reader& r, const YAML::Node& n, const std::string& path, SceneSpec* s) {
  const Map m(r, n, path, {"entity", "interaction", "security", "damping"});
  ComDamperSpec d;
  d.source = m.source();
  d.entity = m.name("entity");
  readDamperGains(m, &d.interaction, &d.security, &d.damping);
  s->com_dampers.push_back(d);
  return d.entity;
}

void reserve(const SceneSpec& s, int* slots, int* rows, int* /*equalities*/) {
  const int n = std::max<int>(1, static_cast<int>(s.com_dampers.size()));
  *slots += n;
  *rows += problem::ComDamper::kRows * n;
}

void build(const SceneSpec& s, const BuildContext& ctx, problem::MultiRobotProblem& p, Scene* /*scene*/) {
  for (std::size_t i = 0; i < s.com_dampers.size(); ++i) {
    const ComDamperSpec& ds = s.com_dampers[i];
    const std::string field = "com_dampers[" + std::to_string(i) + "]";
    const int entity = ctx.entity(ds.entity, ds.source, field + ".entity");
    if (p.addConstraint(
            std::make_unique<problem::ComDamper>(entity, ds.interaction, ds.security, ds.damping)) < 0) {
      BuildContext::fail(ds.source, field, p.lastError());
    }
  }
}

}  // namespace

ConstraintKindEntry comDamperKind() {
  return {"com_dampers", "entity", "com_damper for entity", read, reserve, build};
}

}  // namespace mrqp::scene
