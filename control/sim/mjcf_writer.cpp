// MJCF text of a scene (see mjcf_writer.hpp and docs/mujoco.md).
#include "sim/mjcf_writer.hpp"

#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sim/model_files.hpp"

namespace mrqp::sim {

namespace {

constexpr int kMaxEntities = 30;  // one contype bit each; bit 30 is the ground
constexpr unsigned kGroundBit = 1u << 30;
constexpr unsigned kAllEntityBits = (1u << 30) - 1u;

std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

std::string vec(const Eigen::Vector3d& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

std::string quat(const Eigen::Quaterniond& q) {
  return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z());
}

Eigen::Quaterniond fromRpy(const Eigen::Vector3d& rpy) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()));
}

Eigen::Vector3d toEigen(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }
Eigen::Quaterniond toEigen(const urdf::Rotation& r) {
  Eigen::Quaterniond q(r.w, r.x, r.y, r.z);
  q.normalize();
  return q;
}

std::string poseAttrs(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  return " pos=\"" + vec(p) + "\" quat=\"" + quat(q) + "\"";
}

std::string poseAttrs(const urdf::Pose& p) { return poseAttrs(toEigen(p.position), toEigen(p.rotation)); }

bool fileExists(const std::string& path) {
  std::ifstream f(path);
  return f.good();
}

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

/// A mesh URI resolved to a file, and the root folder of its package (empty for a plain path).
struct ResolvedMesh {
  std::string file;
  std::string package_root;
};

ResolvedMesh resolveMesh(const std::string& uri, const std::string& urdf_dir,
                         const std::vector<std::string>& package_path) {
  ResolvedMesh out;
  const std::string pkg = "package://";
  const std::string file = "file://";
  if (uri.compare(0, pkg.size(), pkg) == 0) {
    const std::string rest = uri.substr(pkg.size());
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? std::string() : rest.substr(slash);
    for (const std::string& dir : package_path) {
      if (fileExists(dir + "/" + package + inside)) {
        out.file = dir + "/" + package + inside;
        out.package_root = dir + "/" + package;
        return out;
      }
    }
    for (const std::string& dir : package_path) {  // the package without the file (COLLADA)
      if (fileExists(dir + "/" + package + "/package.xml") || fileExists(dir + "/" + package + "/convex")) {
        out.package_root = dir + "/" + package;
      }
    }
    return out;
  }
  std::string path = uri.compare(0, file.size(), file) == 0 ? uri.substr(file.size()) : uri;
  if (!path.empty() && path[0] != '/') {
    path = urdf_dir + "/" + path;
  }
  if (fileExists(path)) {
    out.file = path;
  }
  return out;
}

bool endsWithNoCase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) {
    return false;
  }
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    const char a = s[s.size() - suffix.size() + i];
    const char b = suffix[i];
    if (std::tolower(static_cast<unsigned char>(a)) != std::tolower(static_cast<unsigned char>(b))) {
      return false;
    }
  }
  return true;
}

/// The points of a qhull output file as sch-core reads it (dimension, counts, the points): the
/// reference convex hull of a link whose meshes are COLLADA.
std::vector<Eigen::Vector3d> readHullPoints(const std::string& path) {
  std::ifstream f(path);
  int dim = 0;
  long count = 0;
  if (!(f >> dim >> count) || dim != 3 || count < 4) {
    throw std::runtime_error(path + ": not a qhull point file (dimension 3, at least 4 points)");
  }
  std::string rest_of_line;
  std::getline(f, rest_of_line);
  std::vector<Eigen::Vector3d> pts;
  for (long i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    if (!(f >> p.x() >> p.y() >> p.z())) {
      throw std::runtime_error(path + ": point " + std::to_string(i + 1) + " of " + std::to_string(count) +
                               " cannot be read");
    }
    pts.push_back(p);
  }
  return pts;
}

std::string rgbaOf(std::size_t entity) {
  static const std::array<const char*, 6> palette = {"0.85 0.85 0.88 1", "0.95 0.55 0.2 1", "0.3 0.55 0.9 1",
                                                     "0.4 0.75 0.4 1",   "0.8 0.35 0.35 1", "0.7 0.6 0.85 1"};
  return palette[entity % palette.size()];
}

/// Everything the writer accumulates while it walks the scene.
struct Writer {
  const scene::SceneSpec& scene;
  const PlantSpec& plant;
  std::vector<std::string> package_path;
  std::ostringstream assets, world;
  std::map<std::string, std::vector<std::string>> geoms_of_entity;   // prefixed geom names
  std::map<std::string, std::vector<std::string>> bodies_of_entity;  // prefixed body names
  std::vector<MjcfEntity> entities;
  std::vector<GeomSpec> visuals;  // of the robot being written
  std::vector<bool> geom_used = std::vector<bool>(plant.geoms.size(), false);

  std::string geomClass(std::size_t entity_index) const {
    const unsigned bit = 1u << entity_index;
    return " contype=\"" + std::to_string(bit) + "\" conaffinity=\"" + std::to_string(kAllEntityBits & ~bit) +
           "\"";
  }

  std::string primitive(const GeomSpec& g) const {
    const Eigen::Quaterniond q = fromRpy(g.pose.rpy);
    switch (g.type) {
      case GeomSpec::Type::Box:
        return "type=\"box\" size=\"" + vec(0.5 * g.size) + "\"" + poseAttrs(g.pose.xyz, q);
      case GeomSpec::Type::Sphere:
        return "type=\"sphere\" size=\"" + num(g.size.x()) + "\"" + poseAttrs(g.pose.xyz, q);
      case GeomSpec::Type::Cylinder:
        return "type=\"cylinder\" size=\"" + num(g.size.x()) + " " + num(0.5 * g.size.y()) + "\"" +
               poseAttrs(g.pose.xyz, q);
      case GeomSpec::Type::Capsule:
        return "type=\"capsule\" size=\"" + num(g.size.x()) + " " + num(0.5 * g.size.y()) + "\"" +
               poseAttrs(g.pose.xyz, q);
    }
    return {};
  }

  void addGeom(std::ostream& out, std::size_t entity_index, const std::string& entity,
               const std::string& body, const std::string& shape) {
    std::vector<std::string>& names = geoms_of_entity[entity];
    const std::string name = body + "/" + std::to_string(names.size());
    names.push_back(name);
    out << "<geom name=\"" << name << "\" " << shape << geomClass(entity_index) << " rgba=\""
        << rgbaOf(entity_index) << "\"/>\n";
  }

  /// The plant section's primitives for this link.
  void addPlantGeoms(std::ostream& out, std::size_t entity_index, const std::string& entity,
                     const std::string& link, const std::string& body, bool is_root) {
    for (std::size_t i = 0; i < plant.geoms.size(); ++i) {
      const GeomSpec& g = plant.geoms[i];
      if (g.entity == entity && (g.link == link || (g.link.empty() && is_root))) {
        addGeom(out, entity_index, entity, body, primitive(g));
        geom_used[i] = true;
      }
    }
  }

  void linkGeoms(std::ostream& out, std::size_t entity_index, const std::string& entity,
                 const urdf::ModelInterface& robot, const urdf::Link& link, const std::string& urdf_dir,
                 const std::string& body) {
    // A plant-section shape with `replace` stands for the link's own geometry.
    for (const GeomSpec& g : plant.geoms) {
      if (g.replace && g.entity == entity && g.link == link.name) {
        return;
      }
    }
    bool hull_done = false;
    for (const urdf::CollisionSharedPtr& c : link.collision_array) {
      if (!c || !c->geometry) {
        continue;
      }
      const urdf::Geometry& g = *c->geometry;
      const std::string at = poseAttrs(c->origin);
      switch (g.type) {
        case urdf::Geometry::SPHERE: {
          const auto& s = static_cast<const urdf::Sphere&>(g);
          addGeom(out, entity_index, entity, body, "type=\"sphere\" size=\"" + num(s.radius) + "\"" + at);
          break;
        }
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(g);
          addGeom(out, entity_index, entity, body,
                  "type=\"box\" size=\"" + vec(0.5 * toEigen(b.dim)) + "\"" + at);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& y = static_cast<const urdf::Cylinder&>(g);
          addGeom(out, entity_index, entity, body,
                  "type=\"cylinder\" size=\"" + num(y.radius) + " " + num(0.5 * y.length) + "\"" + at);
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(g);
          const ResolvedMesh r = resolveMesh(m.filename, urdf_dir, package_path);
          const std::string mesh_name = body + "/mesh" + std::to_string(geoms_of_entity[entity].size());
          if (!r.file.empty() && endsWithNoCase(r.file, ".stl")) {
            assets << "<mesh name=\"" << mesh_name << "\" file=\"" << r.file << "\" scale=\""
                   << vec(toEigen(m.scale)) << "\"/>\n";
            addGeom(out, entity_index, entity, body, "type=\"mesh\" mesh=\"" + mesh_name + "\"" + at);
          } else if (!hull_done && !r.package_root.empty()) {
            // MuJoCo 2.2 reads no COLLADA: the package's reference convex hull of the link.
            const std::string hull =
                r.package_root + "/convex/" + robot.getName() + "/" + link.name + "-ch.txt";
            if (fileExists(hull)) {
              std::ostringstream v;
              for (const Eigen::Vector3d& p : readHullPoints(hull)) {
                v << vec(p) << " ";
              }
              assets << "<mesh name=\"" << mesh_name << "\" vertex=\"" << v.str() << "\"/>\n";
              addGeom(out, entity_index, entity, body, "type=\"mesh\" mesh=\"" + mesh_name + "\"" + at);
              hull_done = true;
            }
          }
          break;
        }
      }
    }
  }

  void linkBody(std::ostream& out, std::size_t entity_index, const std::string& entity,
                const urdf::ModelInterface& robot, const urdf::Link& link, const std::string& urdf_dir,
                MjcfEntity& info, bool is_root) {
    const std::string body = entity + "/" + link.name;
    bodies_of_entity[entity].push_back(body);
    info.links.push_back(link.name);
    if (const urdf::InertialSharedPtr& in = link.inertial; in && in->mass > 0.0) {
      // MJCF's fullinertia is in the body frame (it takes no orientation of its own).
      Eigen::Matrix3d I;
      I << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
      const Eigen::Matrix3d R = toEigen(in->origin.rotation).toRotationMatrix();
      const Eigen::Matrix3d Ib = R * I * R.transpose();
      out << "<inertial pos=\"" << vec(toEigen(in->origin.position)) << "\" mass=\"" << num(in->mass)
          << "\" fullinertia=\"" << num(Ib(0, 0)) << " " << num(Ib(1, 1)) << " " << num(Ib(2, 2)) << " "
          << num(Ib(0, 1)) << " " << num(Ib(0, 2)) << " " << num(Ib(1, 2)) << "\"/>\n";
    }
    linkGeoms(out, entity_index, entity, robot, link, urdf_dir, body);
    for (const GeomSpec& g : visuals) {
      if (g.link == link.name) {
        // Half transparent: drawn only, and never hiding what acts on it.
        out << "<geom " << primitive(g) << " contype=\"0\" conaffinity=\"0\" group=\"1\" rgba=\""
            << rgbaOf(entity_index).substr(0, rgbaOf(entity_index).size() - 1) << "0.4\"/>\n";
      }
    }
    addPlantGeoms(out, entity_index, entity, link.name, body, is_root);
    for (const urdf::JointSharedPtr& j : link.child_joints) {
      const urdf::LinkConstSharedPtr child = robot.getLink(j->child_link_name);
      if (!child) {
        continue;
      }
      out << "<body name=\"" << entity << "/" << child->name << "\""
          << poseAttrs(j->parent_to_joint_origin_transform) << ">\n";
      const Eigen::Vector3d axis = toEigen(j->axis);
      switch (j->type) {
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC: {
          const bool hinge = j->type != urdf::Joint::PRISMATIC;
          out << "<joint name=\"" << entity << "/" << j->name << "\" type=\"" << (hinge ? "hinge" : "slide")
              << "\" axis=\"" << vec(axis) << "\"";
          if (j->type != urdf::Joint::CONTINUOUS && j->limits && j->limits->upper > j->limits->lower) {
            out << " limited=\"true\" range=\"" << num(j->limits->lower) << " " << num(j->limits->upper)
                << "\"";
          } else {
            out << " limited=\"false\"";
          }
          out << "/>\n";
          info.joints.push_back(j->name);
          if (j->mimic) {
            info.mimics.push_back(
                MjcfMimic{j->name, j->mimic->joint_name, j->mimic->multiplier, j->mimic->offset});
          }
          break;
        }
        case urdf::Joint::FIXED:
          break;
        default:
          throw std::runtime_error("joint '" + j->name + "' of entity '" + entity +
                                   "': floating and planar joints inside a robot are not supported");
      }
      linkBody(out, entity_index, entity, robot, *child, urdf_dir, info, false);
      out << "</body>\n";
    }
  }

  void robot(std::size_t index, const scene::EntitySpec& e) {
    const std::string urdf_path = builtinModelUrdf(e.model);
    if (urdf_path.empty()) {
      throw std::runtime_error(e.source.file + ":" + std::to_string(e.source.line) + ": entities." + e.name +
                               ".model: no URDF known for model '" + e.model +
                               "' (the MuJoCo plant knows panda, jvrc1, door and rigid_object)");
    }
    const urdf::ModelInterfaceSharedPtr robot = urdf::parseURDFFile(urdf_path);
    if (!robot || !robot->getRoot()) {
      throw std::runtime_error(urdf_path + ": cannot be parsed as URDF");
    }
    MjcfEntity info;
    info.name = e.name;
    info.model = e.model;
    info.floating = builtinModelFloating(e.model);
    visuals = builtinModelVisuals(e.model);
    info.root_body = e.name + "/" + robot->getRoot()->name;
    world << "<body name=\"" << info.root_body << "\"" << poseAttrs(e.pose.xyz, fromRpy(e.pose.rpy)) << ">\n";
    if (info.floating) {
      world << "<freejoint name=\"" << e.name << "/root\"/>\n";
    }
    linkBody(world, index, e.name, *robot, *robot->getRoot(), directoryOf(urdf_path), info, true);
    world << "</body>\n";
    entities.push_back(info);
  }

  void rigidObject(std::size_t index, const scene::EntitySpec& e) {
    MjcfEntity info;
    info.name = e.name;
    info.model = e.model;
    info.floating = true;
    info.rigid_object = true;
    info.root_body = e.name + "/" + e.name;
    info.links.push_back(e.name);
    bodies_of_entity[e.name].push_back(info.root_body);
    const scene::RigidObjectSpec& o = e.object;
    const Eigen::Matrix3d& I = o.inertia;
    world << "<body name=\"" << info.root_body << "\"" << poseAttrs(e.pose.xyz, fromRpy(e.pose.rpy))
          << ">\n<freejoint name=\"" << e.name << "/root\"/>\n<inertial pos=\"" << vec(o.com) << "\" mass=\""
          << num(o.mass) << "\" fullinertia=\"" << num(I(0, 0)) << " " << num(I(1, 1)) << " " << num(I(2, 2))
          << " " << num(I(0, 1)) << " " << num(I(0, 2)) << " " << num(I(1, 2)) << "\"/>\n";
    bool has_geom = false;
    for (const GeomSpec& g : plant.geoms) {
      has_geom = has_geom || g.entity == e.name;
    }
    if (has_geom) {
      addPlantGeoms(world, index, e.name, e.name, info.root_body, true);
    } else {
      // The box of the same mass and principal moments (about the CoM, in object axes; off-
      // diagonal terms ignored): a stand-in until the plant section gives the real shape.
      const double m = o.mass;
      const auto side = [&](double a, double b, double c) {
        return std::sqrt(std::max(6.0 * (a + b - c) / m, 1e-6));
      };
      GeomSpec g;
      g.type = GeomSpec::Type::Box;
      g.size = Eigen::Vector3d(side(I(1, 1), I(2, 2), I(0, 0)), side(I(0, 0), I(2, 2), I(1, 1)),
                               side(I(0, 0), I(1, 1), I(2, 2)));
      g.pose.xyz = o.com;
      addGeom(world, index, e.name, info.root_body, primitive(g));
    }
    world << "</body>\n";
    entities.push_back(info);
  }
};

void checkPlantNames(const scene::SceneSpec& scene, const PlantSpec& plant) {
  const auto known = [&](const std::string& n) {
    if (n == "ground") {
      return true;
    }
    for (const scene::EntitySpec& e : scene.entities) {
      if (e.name == n) {
        return true;
      }
    }
    return false;
  };
  const auto where = [](const scene::Source& s) { return s.file + ":" + std::to_string(s.line) + ": "; };
  for (std::size_t i = 0; i < plant.pairs.size(); ++i) {
    for (const std::string* n : {&plant.pairs[i].a, &plant.pairs[i].b}) {
      if (!known(*n)) {
        throw std::runtime_error(where(plant.pairs[i].source) + "plant.pairs[" + std::to_string(i) +
                                 "].between: unknown entity '" + *n + "'");
      }
    }
  }
  for (std::size_t i = 0; i < plant.geoms.size(); ++i) {
    if (!known(plant.geoms[i].entity) || plant.geoms[i].entity == "ground") {
      throw std::runtime_error(where(plant.geoms[i].source) + "plant.geoms[" + std::to_string(i) +
                               "].entity: unknown entity '" + plant.geoms[i].entity + "'");
    }
  }
  for (std::size_t i = 0; i < plant.grasps.size(); ++i) {
    bool found = false;
    for (const scene::ContactSpec& c : scene.contacts) {
      found = found || (c.name == plant.grasps[i].contact && !c.other_entity.empty());
    }
    if (!found) {
      throw std::runtime_error(where(plant.grasps[i].source) + "plant.grasps[" + std::to_string(i) + "]: '" +
                               plant.grasps[i].contact + "' is not a contact between two entities of the scene");
    }
  }
}

}  // namespace

MjcfModel writeMjcf(const scene::SceneSpec& scene, const PlantSpec& plant,
                    const std::vector<MjcfWeld>& welds_in) {
  if (scene.entities.size() > static_cast<std::size_t>(kMaxEntities)) {
    throw std::runtime_error(scene.file + ": the MuJoCo plant takes at most " + std::to_string(kMaxEntities) +
                             " entities");
  }
  checkPlantNames(scene, plant);
  Writer w{scene, plant, plant.package_path.empty() ? defaultPackagePath() : plant.package_path,
           {},    {},    {},
           {},    {},    {}};
  for (std::size_t i = 0; i < scene.entities.size(); ++i) {
    const scene::EntitySpec& e = scene.entities[i];
    if (e.model == "rigid_object") {
      w.rigidObject(i, e);
    } else {
      w.robot(i, e);
    }
  }

  for (std::size_t i = 0; i < plant.geoms.size(); ++i) {
    if (!w.geom_used[i]) {
      const GeomSpec& g = plant.geoms[i];
      throw std::runtime_error(g.source.file + ":" + std::to_string(g.source.line) + ": plant.geoms[" +
                               std::to_string(i) + "].link: entity '" + g.entity + "' has no link '" +
                               g.link + "'");
    }
  }

  MjcfModel out;
  std::ostringstream x;
  const scene::SettingsSpec& st = scene.settings;
  x << "<mujoco model=\"mrqp-scene\">\n"
    << "<compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" boundinertia=\"0\"/>\n"
    << "<size njmax=\"4000\" nconmax=\"800\"/>\n"
    << "<option timestep=\"" << num(plant.timestep) << "\" gravity=\"" << vec(st.gravity)
    << "\" cone=\"pyramidal\" integrator=\"" << (plant.integrator == "implicit" ? "implicit" : "Euler")
    << "\"/>\n"
    << "<visual><global offwidth=\"1920\" offheight=\"1080\"/><quality shadowsize=\"2048\"/></visual>\n"
    << "<default><geom friction=\"" << num(plant.contact.friction) << " 0.005 0.0001\" solref=\""
    << num(plant.contact.timeconst) << " " << num(plant.contact.dampratio) << "\"/></default>\n"
    << "<asset>\n"
    << "<texture name=\"grid\" type=\"2d\" builtin=\"checker\" rgb1=\"0.25 0.3 0.35\" "
       "rgb2=\"0.35 0.4 0.45\" width=\"512\" height=\"512\"/>\n"
    << "<material name=\"grid\" texture=\"grid\" texrepeat=\"8 8\" reflectance=\"0.1\"/>\n"
    << w.assets.str() << "</asset>\n"
    << "<worldbody>\n"
    << "<light pos=\"0 0 5\" dir=\"0 0 -1\" directional=\"true\" diffuse=\"0.7 0.7 0.7\"/>\n"
    << "<light pos=\"3 -3 4\" dir=\"-0.5 0.5 -0.7\" directional=\"true\" diffuse=\"0.3 0.3 0.3\" "
       "castshadow=\"false\"/>\n"
    << "<geom name=\"ground\" type=\"plane\" size=\"10 10 0.1\" material=\"grid\" contype=\"" << kGroundBit
    << "\" conaffinity=\"" << kAllEntityBits << "\"/>\n"
    << w.world.str() << "</worldbody>\n";

  // Contact parameters per pair: explicit pairs, and the same bodies excluded from MuJoCo's
  // dynamic detection (which would otherwise add a second contact with the defaults). A pair
  // that does not collide is only excluded.
  std::ostringstream contact;
  for (const PairSpec& p : plant.pairs) {
    const auto geoms = [&](const std::string& e) {
      return e == "ground" ? std::vector<std::string>{"ground"} : w.geoms_of_entity[e];
    };
    const auto bodies = [&](const std::string& e) {
      return e == "ground" ? std::vector<std::string>{"world"} : w.bodies_of_entity[e];
    };
    for (const std::string& g1 : p.collide ? geoms(p.a) : std::vector<std::string>{}) {
      for (const std::string& g2 : geoms(p.b)) {
        contact << "<pair geom1=\"" << g1 << "\" geom2=\"" << g2 << "\" condim=\"3\" friction=\""
                << num(p.params.friction) << " " << num(p.params.friction)
                << " 0.005 0.0001 0.0001\" solref=\"" << num(p.params.timeconst) << " "
                << num(p.params.dampratio) << "\"/>\n";
      }
    }
    for (const std::string& b1 : bodies(p.a)) {
      for (const std::string& b2 : bodies(p.b)) {
        if (b1 != b2) {
          contact << "<exclude body1=\"" << b1 << "\" body2=\"" << b2 << "\"/>\n";
        }
      }
    }
  }
  if (!contact.str().empty()) {
    x << "<contact>\n" << contact.str() << "</contact>\n";
  }

  // Grasps: a weld between the bodies of the two frames of the contact.
  const auto bodyOfFrame = [&](const std::string& entity, const std::string& frame) -> std::string {
    for (const MjcfEntity& e : w.entities) {
      if (e.name != entity) {
        continue;
      }
      if (e.rigid_object) {
        return e.root_body;
      }
      for (const std::string& l : e.links) {
        if (l == frame) {
          return entity + "/" + l;
        }
      }
    }
    return {};
  };
  std::ostringstream eq;
  for (const MjcfEntity& e : w.entities) {
    for (const MjcfMimic& m : e.mimics) {
      eq << "<joint name=\"mimic/" << e.name << "/" << m.joint << "\" joint1=\"" << e.name << "/" << m.joint
         << "\" joint2=\"" << e.name << "/" << m.master << "\" polycoef=\"" << num(m.offset) << " "
         << num(m.multiplier) << " 0 0 0\"/>\n";
    }
  }
  for (const GraspSpec& grasp : plant.grasps) {
    const std::string& g = grasp.contact;
    for (const scene::ContactSpec& c : scene.contacts) {
      if (c.name != g) {
        continue;
      }
      MjcfWeld weld;
      weld.contact = g;
      weld.body1 = bodyOfFrame(c.other_entity, c.other_frame);
      weld.body2 = bodyOfFrame(c.entity, c.frame);
      if (weld.body1.empty() || weld.body2.empty()) {
        throw std::runtime_error(c.source.file + ":" + std::to_string(c.source.line) +
                                 ": plant.grasps: contact '" + g + "': no body for frame '" +
                                 (weld.body1.empty() ? c.other_frame : c.frame) + "'");
      }
      for (const MjcfWeld& known : welds_in) {
        if (known.contact == g && known.relative_known) {
          weld = known;
        }
      }
      weld.point_only = grasp.hold == GraspSpec::Hold::Point;
      weld.point = grasp.point;
      const Eigen::Vector3d point = grasp.point_given ? grasp.point : Eigen::Vector3d::Zero();
      const std::string solref = " solref=\"" + num(grasp.timeconst) + " " + num(grasp.dampratio) + "\"/>\n";
      if (weld.point_only) {
        // MuJoCo's connect: anchor is the point in body1.
        eq << "<connect name=\"grasp/" << g << "\" body1=\"" << weld.body1 << "\" body2=\"" << weld.body2
           << "\" anchor=\"" << vec(weld.relative_known ? Eigen::Vector3d(weld.relative * point) : point) << "\""
           << solref;
      } else {
        eq << "<weld name=\"grasp/" << g << "\" body1=\"" << weld.body1 << "\" body2=\"" << weld.body2 << "\"";
        if (weld.relative_known) {
          // MuJoCo holds body1 · relpos = body2 · anchor: relpos is the weld's point in body1.
          const Eigen::Quaterniond q(weld.relative.rotation());
          eq << " relpose=\"" << vec(weld.relative * point) << " " << quat(q) << "\"";
        }
        if (grasp.point_given) {
          eq << " anchor=\"" << vec(point) << "\"";
        }
        eq << solref;
      }
      out.welds.push_back(weld);
    }
  }
  if (!eq.str().empty()) {
    x << "<equality>\n" << eq.str() << "</equality>\n";
  }
  // Every joint but the mimic ones has its drive: force = b0 + b1·q + b2·q̇, clamped, with the
  // numbers written by the plant from its servo command (b0 = τ_ff + kp q_ref + kd v_ref,
  // b1 = −kp, b2 = −kd, or with the Euler integrator b2 = 0 and kd as the joint's damping, which
  // that integrator takes implicitly).
  std::ostringstream act;
  for (const MjcfEntity& e : w.entities) {
    for (const std::string& j : e.joints) {
      const bool mimic =
          std::any_of(e.mimics.begin(), e.mimics.end(), [&](const MjcfMimic& m) { return m.joint == j; });
      if (!mimic) {
        act << "<general name=\"" << e.name << "/" << j << "\" joint=\"" << e.name << "/" << j
            << "\" gaintype=\"fixed\" gainprm=\"0\" biastype=\"affine\" biasprm=\"0 0 0\" "
               "forcelimited=\"true\" forcerange=\"-1 1\" ctrllimited=\"false\"/>\n";
      }
    }
  }
  if (!act.str().empty()) {
    x << "<actuator>\n" << act.str() << "</actuator>\n";
  }
  x << "</mujoco>\n";
  out.xml = x.str();
  out.entities = w.entities;
  return out;
}

}  // namespace mrqp::sim
