#include "urdf_loader.hpp"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "bounded_file.hpp"
#include "convex_hull.hpp"
#include "generator_limits.hpp"
#include "mesh_reader.hpp"
#include "name_rule.hpp"
#include "parent_walk.hpp"
#include "unit_direction.hpp"
#include "urdf_preparse.hpp"

namespace mrqp::gen {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Collects what urdfdom reports through console_bridge while one parse runs.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  CapturedLog() { console_bridge::useOutputHandler(this); }
  ~CapturedLog() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    // urdfdom's text holds names as read: shown printable, on one line
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(printable(text, 400));
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) error = true;
  }
  std::vector<std::string> messages;
  /// urdfdom ignores a failed <link> sub-element (e.g. ixx="inf") and returns a model anyway.
  bool error = false;
};

/// Names the element behind urdfdom messages that name none: a missing <robot> element (not XML at all),
/// or "no root link" (finds the joint that closes the loop). Empty when neither applies.
std::string describeParseFailure(const std::string& xml) {
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) return "no <robot> element (not an XML URDF document)";
  std::vector<std::string> links;
  for (const TiXmlElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
    if (const char* n = l->Attribute("name")) links.push_back(n);
  std::map<std::string, std::pair<std::string, std::string>> parentOf;  // child link -> (joint, parent link)
  for (const TiXmlElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const TiXmlElement* parent = j->FirstChildElement("parent");
    const TiXmlElement* child = j->FirstChildElement("child");
    const char* name = j->Attribute("name");
    if (!name || !parent || !child || !parent->Attribute("link") || !child->Attribute("link")) continue;
    parentOf.emplace(child->Attribute("link"),
                     std::make_pair(std::string(name), std::string(parent->Attribute("link"))));
  }
  if (links.empty()) return {};
  for (const auto& l : links)
    if (!parentOf.count(l)) return {};  // there is a root: not this defect
  std::set<std::string> seen;
  std::string cur = links.front();
  while (parentOf.count(cur)) {
    if (!seen.insert(cur).second)
      return "joint '" + printable(parentOf[cur].first) + "': closes a kinematic cycle through link '" +
             printable(cur) + "' (no root link: every link has a parent joint)";
    cur = parentOf[cur].second;
  }
  return {};
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw ModelError(source + ": " + what);
}

bool finite(const urdf::Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Eigen::Vector3d toEigen(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

struct Placement {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Placement operator*(const Placement& o) const { return {R * o.R, R * o.p + p}; }
};

Placement toPlacement(const urdf::Pose& pose) {
  const auto& r = pose.rotation;
  Eigen::Quaterniond q(r.w, r.x, r.y, r.z);
  Placement out;
  out.R = q.normalized().toRotationMatrix();
  out.p = toEigen(pose.position);
  return out;
}

void checkFinite(const std::string& source, const std::string& element, const char* field, double x) {
  if (!std::isfinite(x)) fail(source, element + ": " + field + " is NaN or infinite");
}

/// `x` finite and within [-max, max] (generator_limits.hpp).
void checkRange(const std::string& source, const std::string& element, const char* field, double x,
                double max) {
  checkFinite(source, element, field, x);
  if (std::fabs(x) > max) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " %g is outside [%g, %g]", x, -max, max);
    fail(source, element + ": " + field + buf);
  }
}

void checkRange(const std::string& source, const std::string& element, const std::string& field,
                const urdf::Vector3& v, double max) {
  checkRange(source, element, (field + "x").c_str(), v.x, max);
  checkRange(source, element, (field + "y").c_str(), v.y, max);
  checkRange(source, element, (field + "z").c_str(), v.z, max);
}

void checkPose(const std::string& source, const std::string& element, const urdf::Pose& pose) {
  const auto& r = pose.rotation;
  if (!finite(pose.position) || !std::isfinite(r.w) || !std::isfinite(r.x) || !std::isfinite(r.y) ||
      !std::isfinite(r.z))
    fail(source, element + ": origin has a NaN or infinite number");
  checkRange(source, element + " origin", "", pose.position, kMaxLength);
}

/// "link 'name'" for messages; names that broke the name rule never get here (checkNames), a
/// reference to a missing element may: shown printable either way.
std::string quoted(const std::string& kind, const std::string& name) {
  return kind + " '" + printable(name) + "'";
}

/// Validates a link's inertial and returns it about the link origin, in link axes.
BodyInertia linkInertia(const std::string& source, const urdf::Link& link, bool allow_nonphysical,
                        std::vector<std::string>& warnings) {
  BodyInertia out;
  if (!link.inertial) return out;
  const auto& in = *link.inertial;
  const std::string el = quoted("link", link.name);
  checkPose(source, el + " inertial", in.origin);
  const double vals[] = {in.mass, in.ixx, in.ixy, in.ixz, in.iyy, in.iyz, in.izz};
  const char* names[] = {"mass", "ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int i = 0; i < 7; ++i)
    checkRange(source, el + " inertial", names[i], vals[i], i == 0 ? kMaxMass : kMaxInertia);
  if (in.mass < 0.0) fail(source, el + ": negative mass " + std::to_string(in.mass));
  Eigen::Matrix3d Ic;
  Ic << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const double scale = std::max(1.0, Ic.cwiseAbs().maxCoeff());
  const double tol = 1e-12 * scale;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Ic);
  const Eigen::Vector3d ev = eig.eigenvalues();  // ascending
  if (ev(0) < -tol) {
    std::ostringstream os;
    os << el << ": inertia is not positive definite (principal moments " << ev(0) << ", " << ev(1) << ", "
       << ev(2) << ")";
    fail(source, os.str());
  }
  if (ev(0) + ev(1) < ev(2) - 1e-9 * std::max(scale, ev(2))) {
    std::ostringstream os;
    os << el << ": inertia violates the triangle inequality (principal moments " << ev(0) << " + " << ev(1)
       << " < " << ev(2) << ")";
    if (!allow_nonphysical)
      fail(source, os.str() + "; --allow-nonphysical-inertia accepts it with a warning");
    warnings.push_back(os.str() + "; kept as given (--allow-nonphysical-inertia)");
  }
  if (in.mass == 0.0 && ev(2) > tol) {
    fail(source, el + ": zero mass with a non-zero rotational inertia");
  }
  if (in.mass > 0.0 && ev(0) <= tol)
    warnings.push_back(el + ": positive mass with a singular rotational inertia (point or line mass)");
  const Placement c = toPlacement(in.origin);
  const Eigen::Matrix3d Irot = c.R * Ic * c.R.transpose();
  Eigen::Matrix3d cx;
  cx << 0, -c.p.z(), c.p.y(), c.p.z(), 0, -c.p.x(), -c.p.y(), c.p.x(), 0;
  out.mass = in.mass;
  out.h = in.mass * c.p;
  out.I = Irot - in.mass * cx * cx;
  return out;
}

/// Adds inertia `b`, placed by `X` (b's frame in a's frame), to `a`.
void addInertia(BodyInertia& a, const BodyInertia& b, const Placement& X) {
  const Eigen::Vector3d Rh = X.R * b.h;
  Eigen::Matrix3d px, rhx;
  px << 0, -X.p.z(), X.p.y(), X.p.z(), 0, -X.p.x(), -X.p.y(), X.p.x(), 0;
  rhx << 0, -Rh.z(), Rh.y(), Rh.z(), 0, -Rh.x(), -Rh.y(), Rh.x(), 0;
  a.I += X.R * b.I * X.R.transpose() - px * rhx - rhx * px - b.mass * px * px;
  a.h += Rh + b.mass * X.p;
  a.mass += b.mass;
}

class TreeBuilder {
 public:
  TreeBuilder(const urdf::ModelInterface& model, std::string source, std::string base_dir,
              const LoadOptions& opt)
      : model_(model), source_(std::move(source)), base_dir_(std::move(base_dir)), opt_(opt) {}

  KinematicTree build() {
    checkNames();
    tree_.robot_name = model_.getName();
    tree_.floating_base = opt_.floating_base;
    validateJoints();
    const urdf::LinkConstSharedPtr root = findRoot();
    if (opt_.floating_base) {
      tree_.nq = 7;
      tree_.nv = 6;
      for (int i = 0; i < 7; ++i) {
        tree_.q_lower.push_back(-kInf);
        tree_.q_upper.push_back(kInf);
      }
      for (int i = 0; i < 6; ++i) {
        tree_.v_limit.push_back(kInf);
        tree_.effort_limit.push_back(kInf);
      }
    }
    TreeBody rootBody;
    rootBody.name = root->name;
    rootBody.joint.kind = opt_.floating_base ? JointKind::Floating : JointKind::Fixed;
    rootBody.joint.name = opt_.floating_base ? "root_joint" : "";
    if (opt_.floating_base) {
      rootBody.joint.q_index = 0;
      rootBody.joint.v_index = 0;
    }
    tree_.bodies.push_back(rootBody);
    walk(*root);
    resolveMimics();
    warnMasslessSubtrees();
    return std::move(tree_);
  }

 private:
  /// Every name that can reach the generated code or a message follows the rule of name_rule.hpp.
  void checkNames() {
    if (const std::string v = nameRuleViolation(model_.getName()); !v.empty())
      fail(source_, "robot name '" + printable(model_.getName()) + "': " + v);
    for (const auto& [name, lp] : model_.links_)
      if (const std::string v = nameRuleViolation(name); !v.empty())
        fail(source_, "link '" + printable(name) + "': name " + v);
    for (const auto& [name, jp] : model_.joints_) {
      if (const std::string v = nameRuleViolation(name); !v.empty())
        fail(source_, "joint '" + printable(name) + "': name " + v);
      if (jp->mimic)
        if (const std::string v = nameRuleViolation(jp->mimic->joint_name); !v.empty())
          fail(source_, "joint '" + printable(name) + "': mimic joint name '" +
                            printable(jp->mimic->joint_name) + "': " + v);
    }
  }

  void validateJoints() {
    for (const auto& [name, jp] : model_.joints_) {
      const auto& j = *jp;
      const std::string el = quoted("joint", name);
      checkPose(source_, el, j.parent_to_joint_origin_transform);
      switch (j.type) {
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC:
        case urdf::Joint::FIXED:
          break;
        case urdf::Joint::PLANAR:
          fail(source_,
               el + ": type planar is not supported (model it as two prismatic and one revolute joint)");
        case urdf::Joint::FLOATING:
          fail(source_,
               el + ": type floating is not supported inside the tree (use --floating-base for the root)");
        default:
          fail(source_, el + ": unknown joint type");
      }
      if (j.type == urdf::Joint::FIXED) continue;
      if (!finite(j.axis)) fail(source_, el + ": axis has a NaN or infinite number");
      if (toEigen(j.axis).cwiseAbs().maxCoeff() < kMinAxisComponent) fail(source_, el + ": axis is zero");
      if (j.limits) {
        const auto& l = *j.limits;
        checkRange(source_, el + " limit", "lower", l.lower, kMaxJointLimit);
        checkRange(source_, el + " limit", "upper", l.upper, kMaxJointLimit);
        checkRange(source_, el + " limit", "velocity", l.velocity, kMaxJointLimit);
        checkRange(source_, el + " limit", "effort", l.effort, kMaxJointLimit);
        if (j.type != urdf::Joint::CONTINUOUS && l.lower > l.upper) {
          std::ostringstream os;
          os << el << ": lower limit " << l.lower << " > upper limit " << l.upper;
          fail(source_, os.str());
        }
        if (l.velocity < 0) fail(source_, el + ": negative velocity limit");
        if (l.effort < 0) fail(source_, el + ": negative effort limit");
      }
      if (j.mimic) {
        checkRange(source_, el + " mimic", "multiplier", j.mimic->multiplier, kMaxMimicFactor);
        checkRange(source_, el + " mimic", "offset", j.mimic->offset, kMaxMimicFactor);
        auto it = model_.joints_.find(j.mimic->joint_name);
        if (it == model_.joints_.end())
          fail(source_, el + ": mimic refers to unknown joint '" + j.mimic->joint_name + "'");
        if (it->second->type == urdf::Joint::FIXED)
          fail(source_, el + ": mimic refers to fixed joint '" + j.mimic->joint_name + "'");
      }
    }
  }

  urdf::LinkConstSharedPtr findRoot() {
    // A link with two parents or a loop is reported by the joint that closes it.
    std::map<std::string, std::string> parentJoint;
    for (const auto& [name, jp] : model_.joints_) {
      if (!model_.getLink(jp->child_link_name))
        fail(source_, quoted("joint", name) + ": child link '" + jp->child_link_name + "' does not exist");
      if (!model_.getLink(jp->parent_link_name))
        fail(source_, quoted("joint", name) + ": parent link '" + jp->parent_link_name + "' does not exist");
      auto [it, inserted] = parentJoint.emplace(jp->child_link_name, name);
      if (!inserted)
        fail(source_, quoted("joint", name) + ": link '" + jp->child_link_name +
                          "' already has parent joint '" + it->second + "' (a cycle or a second parent)");
    }
    std::vector<std::string> roots;
    for (const auto& [name, lp] : model_.links_)
      if (!parentJoint.count(name)) roots.push_back(name);
    if (roots.empty()) fail(source_, "no root link: every link has a parent (the joints form a cycle)");
    if (roots.size() > 1) {
      std::string list;
      for (const auto& r : roots) list += (list.empty() ? "'" : ", '") + r + "'";
      fail(source_, "several root links: " + list + " (the tree must have exactly one root)");
    }
    // Cycle detection: walking up from every link must reach the root (parent_walk.hpp: linear).
    std::vector<const std::string*> names;
    std::map<std::string, int> index;
    for (const auto& [name, lp] : model_.links_) {
      index.emplace(name, static_cast<int>(names.size()));
      names.push_back(&name);
    }
    std::vector<int> parent(names.size(), -1);
    for (std::size_t i = 0; i < names.size(); ++i)
      if (auto it = parentJoint.find(*names[i]); it != parentJoint.end())
        parent[i] = index.at(model_.joints_.at(it->second)->parent_link_name);
    if (const int c = firstNodeOnCycle(parent); c >= 0) {
      const std::string& link = *names[idx(c)];
      fail(source_,
           quoted("joint", parentJoint[link]) + ": closes a kinematic cycle through " + quoted("link", link));
    }
    return model_.getLink(roots.front());
  }

  /// Depth-first pre-order walk from the root, children in the order of their joint names, with an
  /// explicit stack (a 10,000-link chain is no deeper on the call stack than one link). A joint is
  /// entered when its child is taken from the stack: fixed joints merge the child into the body.
  void walk(const urdf::Link& root) {
    struct Pending {
      const urdf::Joint* joint;  ///< null for the root
      int body;                  ///< the parent's body
      Placement X_body_parent;   ///< the parent link in that body
    };
    std::vector<Pending> stack{{nullptr, 0, Placement{}}};
    std::vector<urdf::JointSharedPtr> children;
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const urdf::Link* link = &root;
      int body = p.body;
      Placement X = p.X_body_parent;
      if (p.joint) {
        const urdf::Joint& j = *p.joint;
        link = model_.getLink(j.child_link_name).get();
        X = p.X_body_parent * toPlacement(j.parent_to_joint_origin_transform);
        if (j.type != urdf::Joint::FIXED) {
          TreeBody nb;
          nb.name = link->name;
          nb.parent = p.body;
          nb.R0 = X.R;
          nb.p0 = X.p;
          nb.joint = makeJoint(j);
          tree_.bodies.push_back(nb);
          body = static_cast<int>(tree_.bodies.size()) - 1;
          X = Placement{};
        }
      }
      visitLink(*link, body, X);
      children.assign(link->child_joints.begin(), link->child_joints.end());
      std::sort(children.begin(), children.end(),
                [](const auto& a, const auto& b) { return a->name < b->name; });
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({it->get(), body, X});
    }
  }

  /// The link's frame, inertia and collision shapes, placed by X_body_link on `body`.
  void visitLink(const urdf::Link& link, int body, const Placement& X_body_link) {
    TreeFrame frame;
    frame.name = link.name;
    frame.body = body;
    frame.R = X_body_link.R;
    frame.p = X_body_link.p;
    tree_.frames.push_back(frame);
    addInertia(tree_.bodies[idx(body)].inertia,
               linkInertia(source_, link, opt_.allow_nonphysical_inertia, tree_.warnings), X_body_link);
    addCollisions(link, body, X_body_link);
  }

  TreeJoint makeJoint(const urdf::Joint& j) {
    TreeJoint out;
    out.name = j.name;
    out.kind = j.type == urdf::Joint::PRISMATIC ? JointKind::Prismatic : JointKind::Revolute;
    out.continuous = j.type == urdf::Joint::CONTINUOUS;
    // (1e300, 1e300, 1e300) is brought to (1, 1, 1) first: its norm would overflow (unit_direction.hpp)
    out.axis = (toEigen(j.axis) / directionDivisor(j.axis.x, j.axis.y, j.axis.z)).normalized();
    if (j.limits) {
      out.has_limits = true;
      out.lower = out.continuous ? -kInf : j.limits->lower;
      out.upper = out.continuous ? kInf : j.limits->upper;
      // As given: effort 0 is a passive joint (the door's hinge), not an unlimited one.
      out.velocity = j.limits->velocity;
      out.effort = j.limits->effort;
      if (out.velocity == 0.0 && !j.mimic)
        tree_.warnings.push_back(quoted("joint", j.name) +
                                 ": velocity limit 0; velocity limits will hold it still");
    } else {
      out.lower = -kInf;
      out.upper = kInf;
      out.velocity = kInf;
      out.effort = kInf;
      if (!out.continuous && !j.mimic)
        tree_.warnings.push_back(quoted("joint", j.name) + ": no <limit>; treated as unlimited");
    }
    if (j.mimic) {
      out.mimic = true;
      out.mimicked = j.mimic->joint_name;
      out.multiplier = j.mimic->multiplier;
      out.offset = j.mimic->offset;
    } else {
      out.q_index = tree_.nq++;
      out.v_index = tree_.nv++;
      tree_.joint_names.push_back(j.name);
      tree_.q_lower.push_back(out.lower);
      tree_.q_upper.push_back(out.upper);
      tree_.v_limit.push_back(out.velocity);
      tree_.effort_limit.push_back(out.effort);
    }
    return out;
  }

  void resolveMimics() {
    std::map<std::string, int> byName;
    for (int i = 0; i < static_cast<int>(tree_.bodies.size()); ++i)
      if (!tree_.bodies[idx(i)].joint.name.empty()) byName[tree_.bodies[idx(i)].joint.name] = i;
    for (auto& b : tree_.bodies) {
      TreeJoint& j = b.joint;
      if (!j.mimic) continue;
      double mult = j.multiplier, off = j.offset;
      std::string target = j.mimicked;
      std::set<std::string> seen{j.name};
      for (;;) {
        if (!seen.insert(target).second)
          fail(source_,
               quoted("joint", j.name) + ": mimic chain forms a cycle through " + quoted("joint", target));
        if (seen.size() > kMaxMimicChain)
          fail(source_, quoted("joint", j.name) + ": mimic chain longer than " +
                            std::to_string(kMaxMimicChain) + " joints (the mimic chain limit)");
        auto it = byName.find(target);
        if (it == byName.end())
          fail(source_, quoted("joint", j.name) + ": mimic refers to " + quoted("joint", target) +
                            " which is not in the tree");
        const TreeJoint& t = tree_.bodies[idx(it->second)].joint;
        if (!t.mimic) {
          j.q_index = t.q_index;
          j.v_index = t.v_index;
          j.mimicked = t.name;
          break;
        }
        // q_j = mult·(m_t·q + o_t) + off
        off += mult * t.offset;
        mult *= t.multiplier;
        target = t.mimicked;
      }
      j.multiplier = mult;
      j.offset = off;
    }
  }

  void warnMasslessSubtrees() {
    const int n = static_cast<int>(tree_.bodies.size());
    std::vector<double> subtreeMass(idx(n), 0.0);
    std::vector<double> subtreeInertia(idx(n), 0.0);
    for (int i = n - 1; i >= 0; --i) {
      subtreeMass[idx(i)] += tree_.bodies[idx(i)].inertia.mass;
      subtreeInertia[idx(i)] += tree_.bodies[idx(i)].inertia.I.trace();
      if (tree_.bodies[idx(i)].parent >= 0) {
        subtreeMass[idx(tree_.bodies[idx(i)].parent)] += subtreeMass[idx(i)];
        subtreeInertia[idx(tree_.bodies[idx(i)].parent)] += subtreeInertia[idx(i)];
      }
    }
    // A coordinate is singular when every joint it drives (itself and its mimics) moves no mass.
    std::map<int, std::pair<bool, int>> coordinate;  // v index -> (all massless, number of mimics)
    std::map<int, std::string> coordinateName;
    for (int i = 0; i < n; ++i) {
      const TreeJoint& j = tree_.bodies[idx(i)].joint;
      if (j.kind != JointKind::Revolute && j.kind != JointKind::Prismatic) continue;
      auto [it, inserted] = coordinate.emplace(j.v_index, std::make_pair(true, 0));
      it->second.first = it->second.first && subtreeMass[idx(i)] == 0.0 && subtreeInertia[idx(i)] == 0.0;
      if (j.mimic)
        ++it->second.second;
      else
        coordinateName[j.v_index] = j.name;
    }
    for (const auto& [v, info] : coordinate) {
      if (!info.first) continue;
      std::string what = quoted("joint", coordinateName[v]);
      if (info.second > 0) what += " (with the " + std::to_string(info.second) + " joints that mimic it)";
      tree_.warnings.push_back(
          what + " moves no mass (massless subtree); the mass matrix is singular along its coordinate");
    }
  }

  void addCollisions(const urdf::Link& link, int body, const Placement& X_body_link) {
    std::vector<urdf::CollisionSharedPtr> collisions = link.collision_array;
    if (collisions.empty() && link.collision) collisions.push_back(link.collision);
    for (const auto& c : collisions) {
      if (!c || !c->geometry) continue;
      const std::string el = quoted("link", link.name) + " collision";
      checkPose(source_, el, c->origin);
      CollisionShape s;
      s.link = link.name;
      s.body = body;
      const Placement X = X_body_link * toPlacement(c->origin);
      s.R = X.R;
      s.p = X.p;
      switch (c->geometry->type) {
        case urdf::Geometry::BOX: {
          const auto& g = static_cast<const urdf::Box&>(*c->geometry);
          if (!finite(g.dim) || g.dim.x < 0 || g.dim.y < 0 || g.dim.z < 0)
            fail(source_, el + ": invalid box size");
          checkRange(source_, el, "box size ", g.dim, kMaxLength);
          s.kind = ShapeKind::Box;
          s.size = toEigen(g.dim);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& g = static_cast<const urdf::Cylinder&>(*c->geometry);
          if (!std::isfinite(g.radius) || !std::isfinite(g.length) || g.radius < 0 || g.length < 0)
            fail(source_, el + ": invalid cylinder size");
          checkRange(source_, el, "cylinder radius", g.radius, kMaxLength);
          checkRange(source_, el, "cylinder length", g.length, kMaxLength);
          s.kind = ShapeKind::Cylinder;
          s.size = {g.radius, g.length, 0.0};
          break;
        }
        case urdf::Geometry::SPHERE: {
          const auto& g = static_cast<const urdf::Sphere&>(*c->geometry);
          if (!std::isfinite(g.radius) || g.radius < 0) fail(source_, el + ": invalid sphere radius");
          checkRange(source_, el, "sphere radius", g.radius, kMaxLength);
          s.kind = ShapeKind::Sphere;
          s.size = {g.radius, 0.0, 0.0};
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& g = static_cast<const urdf::Mesh&>(*c->geometry);
          checkRange(source_, el, "mesh scale ", g.scale, kMaxMeshScale);
          const std::string file = resolveMeshUri(g.filename, base_dir_, opt_.package_paths);
          if (file.empty()) {
            tree_.warnings.push_back(el + ": mesh '" + printable(g.filename, 400) +
                                     "' not found; no collision shape");
            continue;
          }
          MeshReadResult mesh = readMeshVertices(file);
          if (!mesh.ok) {
            tree_.warnings.push_back(el + ": " + printable(mesh.error, 400) + "; no collision shape");
            continue;
          }
          const Eigen::Vector3d scale = toEigen(g.scale);
          for (auto& v : mesh.vertices) {
            v = v.cwiseProduct(scale);
            if (!(v.cwiseAbs().maxCoeff() <= kMaxLength)) {
              char buf[160];
              std::snprintf(buf, sizeof buf, "a vertex at (%g, %g, %g) after scale is outside [%g, %g]",
                            v.x(), v.y(), v.z(), -kMaxLength, kMaxLength);
              fail(source_, el + ": mesh '" + printable(g.filename, 400) + "': " + buf);
            }
          }
          s.kind = ShapeKind::ConvexMesh;
          s.vertices = convexHull(mesh.vertices).vertices;
          if (s.vertices.empty()) {
            tree_.warnings.push_back(el + ": mesh '" + printable(g.filename, 400) +
                                     "' has no vertices; no collision shape");
            continue;
          }
          break;
        }
      }
      tree_.shapes.push_back(std::move(s));
    }
  }

  const urdf::ModelInterface& model_;
  std::string source_;
  std::string base_dir_;
  const LoadOptions& opt_;
  KinematicTree tree_;
};

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == std::string::npos ? std::string(".") : path.substr(0, pos);
}

}  // namespace

KinematicTree loadUrdfString(const std::string& xml, const std::string& source, const std::string& base_dir,
                             const LoadOptions& options) {
  // Size, nesting and counts checked first; urdfdom parses the canonical text (urdf_preparse.hpp).
  const std::string text = canonicalUrdf(xml, source);
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> parserMessages;
  {
    CapturedLog log;
    try {
      model = urdf::parseURDF(text);
    } catch (const std::exception& e) {
      log.messages.push_back(e.what());
    }
    parserMessages = log.messages;
    if (log.error) model.reset();
  }
  if (!model) {
    std::string why;
    for (const auto& m : parserMessages) why += (why.empty() ? "" : "; ") + m;
    if (why.empty()) why = "not a valid URDF document";
    const std::string detail = describeParseFailure(text);
    if (!detail.empty()) why += "; " + detail;
    fail(source, "URDF parse error: " + why);
  }
  // urdfdom's links own their children: the model, released from a root after its chain, would
  // release the chain recursively. Its links are unlinked first, whatever build() does.
  struct Unlink {
    urdf::ModelInterface& m;
    ~Unlink() {
      for (auto& entry : m.links_) {
        entry.second->child_links.clear();
        entry.second->child_joints.clear();
      }
    }
  } unlink{*model};
  TreeBuilder builder(*model, source, base_dir, options);
  return builder.build();
}

KinematicTree loadUrdfFile(const std::string& path, const LoadOptions& options) {
  const BoundedRead file = readFileAtMost(path, kMaxUrdfBytes, "URDF ");
  if (!file.ok) throw ModelError(path + (file.too_large ? ": " : ": cannot open file: ") + file.error);
  return loadUrdfString(file.data, path, directoryOf(path), options);
}

}  // namespace mrqp::gen
