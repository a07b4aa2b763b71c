// Scene list `collisions` (problem::CollisionConstraint, docs/collision.md): velocity-damper
// collision avoidance between the links of one entity (self-collision) or of two entities.
//
//   collisions:
//     - name: arms
//       entities: [left, right]        # one name: self-collision of that entity
//       links_a: [panda_link5, ...]    # optional: default every link with shapes
//       links_b: [...]
//       interaction: 0.10              # δi (m), default 0.10
//       security: 0.02                 # δs (m), default 0.02
//       damping: 0.5                   # ξ (m/s), default 0.5
//       pairs: [{a: panda_hand, b: panda_hand, interaction: 0.15, security: 0.05, damping: 0.3}]
//       exclude: [[panda_link0, panda_link0]]
//       max_rows: 16                   # inequality rows reserved (pairs active at once)
//       geometry: {left: file.yaml}    # optional per entity; default the model's built-in file
//
// Self-collision pairs leave out adjacent bodies (found from the frames' Jacobians: the same set
// of moving joints, or one more) and the pairs the geometry file's SRDF disables.
#include <memory>
#include <set>

#include "scene/constraint_kind.hpp"
#include "scene/scene_builder.hpp"
#include "scene/yaml_reader.hpp"

#ifdef MRQP_WITH_COLLISION
#include "collision/collision_constraint.hpp"
#include "scene/constraint_kinds/collision_geometry.hpp"
#endif

namespace mrqp::scene {

namespace {

constexpr const char* kKey = "collisions";

struct CollisionGains {
  double interaction = 0.10, security = 0.02, damping = 0.5;
};

struct CollisionPairSpec {
  std::string a, b;
  CollisionGains gains;
  Source source;
};

struct CollisionSpec {
  std::vector<std::string> entities;
  std::vector<std::string> links_a, links_b;
  CollisionGains gains;
  std::vector<CollisionPairSpec> pairs;
  std::vector<std::pair<std::string, std::string>> exclude;
  int max_rows = 16;
  std::map<std::string, std::string> geometry;
  Source source;
};

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == std::string::npos ? std::string(".") : path.substr(0, pos);
}

std::string read(const Reader& r, const YAML::Node& n, const std::string& path, SceneSpec* s) {
  const Map m(r, n, path,
              {"name", "entities", "links_a", "links_b", "interaction", "security", "damping", "pairs",
               "exclude", "max_rows", "geometry"});
  CollisionSpec c;
  c.source = m.source();
  const std::string name = m.has("name") ? m.name("name") : std::string();
  c.entities = r.names(m.require("entities"), m.at("entities"));
  if (c.entities.empty() || c.entities.size() > 2) {
    r.fail(m.require("entities"), m.at("entities"), "expected one entity (self-collision) or two");
  }
  if (m.has("links_a")) c.links_a = r.names(m.require("links_a"), m.at("links_a"));
  if (m.has("links_b")) c.links_b = r.names(m.require("links_b"), m.at("links_b"));
  readDamperGains(m, &c.gains.interaction, &c.gains.security, &c.gains.damping);
  if (const YAML::Node* pn = m.find("pairs")) {
    const std::vector<YAML::Node> items = r.list(*pn, m.at("pairs"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      const Map pm(r, items[i], item(m.at("pairs"), i), {"a", "b", "interaction", "security", "damping"});
      CollisionPairSpec ps;
      ps.source = pm.source();
      ps.a = pm.name("a");
      ps.b = pm.name("b");
      ps.gains = c.gains;
      readDamperGains(pm, &ps.gains.interaction, &ps.gains.security, &ps.gains.damping);
      c.pairs.push_back(ps);
    }
  }
  if (const YAML::Node* en = m.find("exclude")) {
    const std::vector<YAML::Node> items = r.list(*en, m.at("exclude"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::vector<YAML::Node> two = r.list(items[i], item(m.at("exclude"), i));
      if (two.size() != 2) r.fail(items[i], item(m.at("exclude"), i), "expected two link names");
      c.exclude.emplace_back(r.name(two[0], item(item(m.at("exclude"), i), 0)),
                             r.name(two[1], item(item(m.at("exclude"), i), 1)));
    }
  }
  c.max_rows = m.integer("max_rows", 1, 4096, c.max_rows);
  if (const YAML::Node* gn = m.find("geometry")) {
    for (const Entry& e : r.entries(*gn, m.at("geometry"))) {
      std::string file = r.name(e.value, child(m.at("geometry"), e.key));
      if (file[0] != '/') file = directoryOf(r.file()) + "/" + file;
      c.geometry[e.key] = file;
    }
  }
  s->constraints.push_back(ConstraintItemSpec{kKey, name, c, c.source});
  return name;
}

void reserve(const SceneSpec& s, int* slots, int* rows, int* /*equalities*/) {
  for (const ConstraintItemSpec& it : s.constraints) {
    if (it.kind != kKey) continue;
    *slots += 1;
    *rows += std::any_cast<const CollisionSpec&>(it.spec).max_rows;
  }
}

#ifdef MRQP_WITH_COLLISION

// Velocity coordinates that move a frame: the non-zero columns of its Jacobian.
std::vector<bool> movingJoints(const problem::Entity& e, int frame) {
  Eigen::MatrixXd J(6, e.nv());
  e.frameJacobian(frame, Eigen::Vector3d::Zero(), J);
  std::vector<bool> out(static_cast<std::size_t>(e.nv()));
  for (int c = 0; c < e.nv(); ++c) out[static_cast<std::size_t>(c)] = J.col(c).norm() > 1e-12;
  return out;
}

// Adjacent: the same moving joints (one rigid body), or one joint more on one side.
bool adjacent(const std::vector<bool>& a, const std::vector<bool>& b) {
  int a_only = 0, b_only = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    a_only += a[i] && !b[i] ? 1 : 0;
    b_only += b[i] && !a[i] ? 1 : 0;
  }
  return (a_only == 0 && b_only <= 1) || (b_only == 0 && a_only <= 1);
}

const EntitySpec* entitySpec(const SceneSpec& s, const std::string& name) {
  for (const EntitySpec& e : s.entities) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

void buildOne(const SceneSpec& s, const CollisionSpec& c, const std::string& name, const std::string& field,
              const BuildContext& ctx, problem::MultiRobotProblem& p, Scene* scene) {
  const int ea = ctx.entity(c.entities[0], c.source, field + ".entities[0]");
  const int eb = c.entities.size() > 1 ? ctx.entity(c.entities[1], c.source, field + ".entities[1]") : ea;
  const bool self = ea == eb;
  // Geometry of each entity.
  std::vector<std::shared_ptr<const void>> keep;
  std::array<std::shared_ptr<collision::ShapeSet>, 2> sets;
  for (int side = 0; side < (self ? 1 : 2); ++side) {
    const std::string& en = c.entities[static_cast<std::size_t>(side)];
    std::string file;
    if (auto it = c.geometry.find(en); it != c.geometry.end()) {
      file = it->second;
    } else {
      const EntitySpec* es = entitySpec(s, en);
      file = es != nullptr ? builtinCollisionGeometry(es->model) : "";
      if (file.empty()) {
        BuildContext::fail(c.source, field + ".geometry",
                           "no collision geometry for entity '" + en + "' (model '" + (es ? es->model : "") +
                               "'): give one with geometry: {" + en + ": FILE}");
      }
    }
    sets[static_cast<std::size_t>(side)] =
        std::make_shared<collision::ShapeSet>(readCollisionGeometryFile(file));
    keep.push_back(sets[static_cast<std::size_t>(side)]);
  }
  if (self) sets[1] = sets[0];
  // Bodies: every shape of the chosen links, per side.
  std::vector<problem::CollisionBody> bodies;
  struct LinkRef {
    std::string link;
    int entity, frame, first, count;
    std::vector<bool> moving;
  };
  std::array<std::vector<LinkRef>, 2> links;
  std::map<std::pair<int, int>, int> made;  // (entity, frame) → first body, shared by both sides
  for (int side = 0; side < 2; ++side) {
    const collision::ShapeSet& set = *sets[static_cast<std::size_t>(side)];
    const int e = side == 0 ? ea : eb;
    const std::vector<std::string>& chosen = side == 0 ? c.links_a : c.links_b;
    const std::string lfield = field + (side == 0 ? ".links_a" : ".links_b");
    std::vector<std::string> names = chosen;
    if (names.empty()) {
      for (const collision::LinkShapes& l : set.links()) {
        if (p.entity(e).frameIndex(l.link) >= 0) names.push_back(l.link);
      }
    }
    p.entity(e).update();
    for (const std::string& ln : names) {
      const collision::LinkShapes* ls = set.find(ln);
      if (ls == nullptr) BuildContext::fail(c.source, lfield, "link '" + ln + "' has no collision shapes");
      const int f = ctx.frame(e, ln, c.source, lfield);
      auto key = std::make_pair(e, f);
      if (!made.count(key)) {
        made[key] = static_cast<int>(bodies.size());
        for (const collision::Shape& sh : ls->shapes) {
          problem::CollisionBody b;
          b.entity = e;
          b.frame = f;
          b.shape = sh;
          b.bound = sh.boundingRadius();
          bodies.push_back(b);
        }
      }
      links[static_cast<std::size_t>(side)].push_back(
          LinkRef{ln, e, f, made[key], static_cast<int>(ls->shapes.size()), movingJoints(p.entity(e), f)});
    }
  }
  std::set<collision::LinkPair> excluded;
  for (const auto& x : c.exclude) excluded.insert(collision::linkPair(x.first, x.second));
  std::set<std::pair<int, int>> seen;  // frame pairs already made (self: a/b symmetric)
  std::vector<problem::CollisionPair> pairs;
  std::vector<bool> used(c.pairs.size(), false);  // each `pairs` entry must name an enabled pair
  for (const LinkRef& la : links[0]) {
    for (const LinkRef& lb : links[1]) {
      if (self) {
        if (la.frame == lb.frame) continue;
        const auto fp = std::minmax(la.frame, lb.frame);
        if (!seen.insert({fp.first, fp.second}).second) continue;
        if (adjacent(la.moving, lb.moving) || sets[0]->disabled(la.link, lb.link)) continue;
      }
      if (excluded.count(collision::linkPair(la.link, lb.link))) continue;
      CollisionGains g = c.gains;
      for (std::size_t o = 0; o < c.pairs.size(); ++o) {
        const CollisionPairSpec& ps = c.pairs[o];
        if (collision::linkPair(ps.a, ps.b) == collision::linkPair(la.link, lb.link)) {
          g = ps.gains;
          used[o] = true;
        }
      }
      for (int i = 0; i < la.count; ++i) {
        for (int j = 0; j < lb.count; ++j) {
          problem::CollisionPair pr;
          pr.a = la.first + i;
          pr.b = lb.first + j;
          pr.interaction = g.interaction;
          pr.security = g.security;
          pr.damping = g.damping;
          pairs.push_back(pr);
        }
      }
    }
  }
  for (std::size_t o = 0; o < c.pairs.size(); ++o) {
    if (!used[o]) {
      BuildContext::fail(c.pairs[o].source, field + ".pairs[" + std::to_string(o) + "]",
                         "no enabled pair between '" + c.pairs[o].a + "' and '" + c.pairs[o].b +
                             "' (unknown, adjacent, disabled or excluded)");
    }
  }
  if (pairs.empty())
    BuildContext::fail(c.source, field, "no collision pair left (adjacent, disabled or excluded)");
  const int max_nv = std::max(p.entity(ea).nv(), p.entity(eb).nv());
  const int id = p.addConstraint(std::make_unique<problem::CollisionConstraint>(
      std::move(bodies), std::move(pairs), c.max_rows, max_nv, std::move(keep)));
  if (id < 0) BuildContext::fail(c.source, field, p.lastError());
  if (!name.empty()) scene->constraints[name] = id;
}

void build(const SceneSpec& s, const BuildContext& ctx, problem::MultiRobotProblem& p, Scene* scene) {
  int i = 0;
  for (const ConstraintItemSpec& it : s.constraints) {
    if (it.kind != kKey) continue;
    buildOne(s, std::any_cast<const CollisionSpec&>(it.spec), it.name,
             std::string(kKey) + "[" + std::to_string(i++) + "]", ctx, p, scene);
  }
}

#else

void build(const SceneSpec& s, const BuildContext& /*ctx*/, problem::MultiRobotProblem& /*p*/,
           Scene* /*scene*/) {
  for (const ConstraintItemSpec& it : s.constraints) {
    if (it.kind == kKey) {
      BuildContext::fail(it.source, kKey, "this build has no collision avoidance (libccd was not found)");
    }
  }
}

#endif

}  // namespace

ConstraintKindEntry collisionKind() { return {kKey, "name", "collision name", read, reserve, build}; }

}  // namespace mrqp::scene
