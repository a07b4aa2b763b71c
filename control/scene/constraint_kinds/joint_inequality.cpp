// Scene list `joint_inequalities` (problem::JointInequality): Σ coeff·q ≤ upper over 1 to 4
// joints, {name, terms: [{entity, joint, coeff}], upper, interaction, security, damping}; one
// inequality row each. Scene::joint_inequalities maps the names to constraint ids.
#include <array>

#include "problem/constraints/joint_inequality.hpp"
#include "scene/constraint_kind.hpp"
#include "scene/scene_builder.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

JointInequalitySpec::Term readTerm(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"entity", "joint", "coeff"});
  JointInequalitySpec::Term t;
  t.entity = m.name("entity");
  t.joint = m.name("joint");
  t.coeff = m.number("coeff", Bound::Any, t.coeff);
  return t;
}

std::string read(const Reader& r, const YAML::Node& n, const std::string& path, SceneSpec* s) {
  const Map m(r, n, path, {"name", "terms", "upper", "interaction", "security", "damping"});
  JointInequalitySpec j;
  j.source = m.source();
  if (m.has("name")) {
    j.name = m.name("name");
  }
  const YAML::Node& terms = m.require("terms");
  const std::vector<YAML::Node> items = r.list(terms, m.at("terms"));
  if (items.empty()) {
    r.fail(terms, m.at("terms"), "expected at least one term");
  }
  for (std::size_t i = 0; i < items.size(); ++i) {
    const JointInequalitySpec::Term t = readTerm(r, items[i], item(m.at("terms"), i));
    for (const JointInequalitySpec::Term& u : j.terms) {
      if (u.entity == t.entity && u.joint == t.joint) {
        r.fail(items[i], item(m.at("terms"), i),
               "joint '" + t.joint + "' of '" + t.entity + "' appears twice");
      }
    }
    j.terms.push_back(t);
  }
  j.upper = r.number(m.require("upper"), m.at("upper"));
  readDamperGains(m, &j.interaction, &j.security, &j.damping);
  s->joint_inequalities.push_back(j);
  return j.name;
}

void reserve(const SceneSpec& s, int* slots, int* rows, int* /*equalities*/) {
  const int n = std::max<int>(1, static_cast<int>(s.joint_inequalities.size()));
  *slots += n;
  *rows += n;
}

void build(const SceneSpec& s, const BuildContext& ctx, problem::MultiRobotProblem& p, Scene* scene) {
  for (std::size_t i = 0; i < s.joint_inequalities.size(); ++i) {
    const JointInequalitySpec& js = s.joint_inequalities[i];
    const std::string field = "joint_inequalities[" + std::to_string(i) + "]";
    if (js.terms.size() > static_cast<std::size_t>(problem::JointInequality::kMaxTerms)) {
      BuildContext::fail(js.source, field + ".terms", "at most 4 terms");
    }
    std::array<problem::JointInequality::Term, problem::JointInequality::kMaxTerms> terms{};
    for (std::size_t k = 0; k < js.terms.size(); ++k) {
      const std::string tf = field + ".terms[" + std::to_string(k) + "]";
      terms[k].entity = ctx.entity(js.terms[k].entity, js.source, tf + ".entity");
      terms[k].joint = ctx.joint(terms[k].entity, js.terms[k].joint, js.source, tf + ".joint");
      terms[k].coeff = js.terms[k].coeff;
    }
    const int id = p.addConstraint(std::make_unique<problem::JointInequality>(
        terms.data(), static_cast<int>(js.terms.size()), js.upper, js.interaction, js.security, js.damping));
    if (id < 0) BuildContext::fail(js.source, field, p.lastError());
    scene->joint_inequalities[js.name] = id;
    scene->constraints[js.name] = id;
  }
}

}  // namespace

ConstraintKindEntry jointInequalityKind() {
  return {"joint_inequalities", "name", "joint inequality name", read, reserve, build};
}

}  // namespace mrqp::scene
