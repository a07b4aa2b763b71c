#include "urdf_loader.hpp"

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "convex_hull.hpp"
#include "mesh_reader.hpp"

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
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
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
      return "joint '" + parentOf[cur].first + "': closes a kinematic cycle through link '" + cur +
             "' (no root link: every link has a parent joint)";
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

void checkPose(const std::string& source, const std::string& element, const urdf::Pose& pose) {
  const auto& r = pose.rotation;
  if (!finite(pose.position) || !std::isfinite(r.w) || !std::isfinite(r.x) || !std::isfinite(r.y) ||
      !std::isfinite(r.z))
    fail(source, element + ": origin has a NaN or infinite number");
}

void checkFinite(const std::string& source, const std::string& element, const char* field, double x) {
  if (!std::isfinite(x)) fail(source, element + ": " + field + " is NaN or infinite");
}

std::string quoted(const std::string& kind, const std::string& name) { return kind + " '" + name + "'"; }

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
  for (int i = 0; i < 7; ++i) checkFinite(source, el + " inertial", names[i], vals[i]);
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
    visit(*root, 0, Placement{});
    resolveMimics();
    warnMasslessSubtrees();
    return std::move(tree_);
  }

 private:
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
      if (toEigen(j.axis).norm() < 1e-12) fail(source_, el + ": axis is zero");
      if (j.limits) {
        const auto& l = *j.limits;
        checkFinite(source_, el + " limit", "lower", l.lower);
        checkFinite(source_, el + " limit", "upper", l.upper);
        checkFinite(source_, el + " limit", "velocity", l.velocity);
        checkFinite(source_, el + " limit", "effort", l.effort);
        if (j.type != urdf::Joint::CONTINUOUS && l.lower > l.upper) {
          std::ostringstream os;
          os << el << ": lower limit " << l.lower << " > upper limit " << l.upper;
          fail(source_, os.str());
        }
        if (l.velocity < 0) fail(source_, el + ": negative velocity limit");
        if (l.effort < 0) fail(source_, el + ": negative effort limit");
      }
      if (j.mimic) {
        checkFinite(source_, el + " mimic", "multiplier", j.mimic->multiplier);
        checkFinite(source_, el + " mimic", "offset", j.mimic->offset);
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
    // Cycle detection: walking up from every link must reach the root.
    for (const auto& [name, lp] : model_.links_) {
      std::set<std::string> seen;
      std::string cur = name;
      while (parentJoint.count(cur)) {
        if (!seen.insert(cur).second)
          fail(source_,
               quoted("joint", parentJoint[cur]) + ": closes a kinematic cycle through link '" + cur + "'");
        cur = model_.joints_.at(parentJoint[cur])->parent_link_name;
      }
    }
    return model_.getLink(roots.front());
  }

  void visit(const urdf::Link& link, int body, const Placement& X_body_link) {
    TreeFrame frame;
    frame.name = link.name;
    frame.body = body;
    frame.R = X_body_link.R;
    frame.p = X_body_link.p;
    tree_.frames.push_back(frame);
    addInertia(tree_.bodies[idx(body)].inertia,
               linkInertia(source_, link, opt_.allow_nonphysical_inertia, tree_.warnings), X_body_link);
    addCollisions(link, body, X_body_link);

    std::vector<urdf::JointSharedPtr> children(link.child_joints.begin(), link.child_joints.end());
    std::sort(children.begin(), children.end(),
              [](const auto& a, const auto& b) { return a->name < b->name; });
    for (const auto& j : children) {
      const urdf::LinkConstSharedPtr child = model_.getLink(j->child_link_name);
      const Placement X = X_body_link * toPlacement(j->parent_to_joint_origin_transform);
      if (j->type == urdf::Joint::FIXED) {
        visit(*child, body, X);
        continue;
      }
      TreeBody nb;
      nb.name = child->name;
      nb.parent = body;
      nb.R0 = X.R;
      nb.p0 = X.p;
      nb.joint = makeJoint(*j);
      tree_.bodies.push_back(nb);
      visit(*child, static_cast<int>(tree_.bodies.size()) - 1, Placement{});
    }
  }

  TreeJoint makeJoint(const urdf::Joint& j) {
    TreeJoint out;
    out.name = j.name;
    out.kind = j.type == urdf::Joint::PRISMATIC ? JointKind::Prismatic : JointKind::Revolute;
    out.continuous = j.type == urdf::Joint::CONTINUOUS;
    out.axis = toEigen(j.axis).normalized();
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
               quoted("joint", j.name) + ": mimic chain forms a cycle through joint '" + target + "'");
        auto it = byName.find(target);
        if (it == byName.end())
          fail(source_,
               quoted("joint", j.name) + ": mimic refers to joint '" + target + "' which is not in the tree");
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
          s.kind = ShapeKind::Box;
          s.size = toEigen(g.dim);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& g = static_cast<const urdf::Cylinder&>(*c->geometry);
          if (!std::isfinite(g.radius) || !std::isfinite(g.length) || g.radius < 0 || g.length < 0)
            fail(source_, el + ": invalid cylinder size");
          s.kind = ShapeKind::Cylinder;
          s.size = {g.radius, g.length, 0.0};
          break;
        }
        case urdf::Geometry::SPHERE: {
          const auto& g = static_cast<const urdf::Sphere&>(*c->geometry);
          if (!std::isfinite(g.radius) || g.radius < 0) fail(source_, el + ": invalid sphere radius");
          s.kind = ShapeKind::Sphere;
          s.size = {g.radius, 0.0, 0.0};
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& g = static_cast<const urdf::Mesh&>(*c->geometry);
          const std::string file = resolveMeshUri(g.filename, base_dir_, opt_.package_paths);
          if (file.empty()) {
            tree_.warnings.push_back(el + ": mesh '" + g.filename + "' not found; no collision shape");
            continue;
          }
          MeshReadResult mesh = readMeshVertices(file);
          if (!mesh.ok) {
            tree_.warnings.push_back(el + ": " + mesh.error + "; no collision shape");
            continue;
          }
          const Eigen::Vector3d scale = toEigen(g.scale);
          for (auto& v : mesh.vertices) v = v.cwiseProduct(scale);
          s.kind = ShapeKind::ConvexMesh;
          s.vertices = convexHull(mesh.vertices).vertices;
          if (s.vertices.empty()) {
            tree_.warnings.push_back(el + ": mesh '" + g.filename + "' has no vertices; no collision shape");
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
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> parserMessages;
  {
    CapturedLog log;
    try {
      model = urdf::parseURDF(xml);
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
    const std::string detail = describeParseFailure(xml);
    if (!detail.empty()) why += "; " + detail;
    fail(source, "URDF parse error: " + why);
  }
  TreeBuilder builder(*model, source, base_dir, options);
  return builder.build();
}

KinematicTree loadUrdfFile(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  return loadUrdfString(ss.str(), path, directoryOf(path), options);
}

}  // namespace mrqp::gen
