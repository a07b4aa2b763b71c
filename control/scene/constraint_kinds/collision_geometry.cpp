// Collision geometry files; see collision_geometry.hpp.
#include "scene/constraint_kinds/collision_geometry.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>

#include "collision/geometry_path.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

std::string directoryOf(const std::string& path) {
  const auto pos = path.find_last_of('/');
  return pos == std::string::npos ? std::string(".") : path.substr(0, pos);
}

}  // namespace

collision::ShapeSet readCollisionGeometryString(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError(file + ":" + std::to_string(e.mark.line + 1) + ": (top level): " + e.msg);
  }
  const Reader r(file);
  const Map top(r, root, "", {"srdf", "links"});
  collision::ShapeSet set;
  for (const Entry& link : r.entries(top.require("links"), "links")) {
    const std::string lpath = child("links", link.key);
    const std::vector<YAML::Node> shapes = r.list(link.value, lpath);
    if (shapes.empty()) r.fail(link.value, lpath, "expected a list of shapes, got an empty list");
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const std::string path = item(lpath, i);
      const Map m(r, shapes[i], path, {"sphere", "capsule", "box", "hull", "xyz", "rpy"});
      int kinds = 0;
      for (const char* k : {"sphere", "capsule", "box", "hull"}) kinds += m.has(k) ? 1 : 0;
      if (kinds != 1) r.fail(shapes[i], path, "expected exactly one of sphere, capsule, box, hull");
      collision::Shape s;
      std::vector<Eigen::Vector3d> hull;
      if (m.has("sphere")) {
        s = collision::makeSphere(m.number("sphere", Bound::Positive, 0.0));
      } else if (m.has("capsule")) {
        const Map c(r, m.require("capsule"), m.at("capsule"), {"radius", "length"});
        s = collision::makeCapsule(r.number(c.require("radius"), c.at("radius"), Bound::Positive),
                                   r.number(c.require("length"), c.at("length"), Bound::NonNegative));
      } else if (m.has("box")) {
        const Eigen::Vector3d size = m.vec3("box", Eigen::Vector3d::Zero());
        if (!(size.minCoeff() >= 0.0)) r.fail(m.require("box"), m.at("box"), "expected sizes >= 0");
        s = collision::makeBox(size);
      } else {
        const std::vector<YAML::Node> pts = r.list(m.require("hull"), m.at("hull"));
        if (pts.empty())
          r.fail(m.require("hull"), m.at("hull"), "expected a list of points, got an empty list");
        for (std::size_t j = 0; j < pts.size(); ++j) hull.push_back(r.vec3(pts[j], item(m.at("hull"), j)));
        s = collision::makeHull(hull.data(), static_cast<int>(hull.size()));
      }
      s.p = m.vec3("xyz", Eigen::Vector3d::Zero());
      s.R = rotationFromRpy(m.vec3("rpy", Eigen::Vector3d::Zero()));
      set.add(link.key, s, hull);
    }
  }
  if (const YAML::Node* n = top.find("srdf")) {
    std::string srdf = r.name(*n, "srdf");
    if (srdf.empty() || srdf[0] != '/') srdf = directoryOf(file) + "/" + srdf;
    std::ifstream f(srdf);
    if (!f) r.fail(*n, "srdf", "cannot read '" + srdf + "'");
    try {
      for (const collision::LinkPair& lp : collision::readSrdfDisabledPairsFile(srdf))
        set.disable(lp.first, lp.second);
    } catch (const std::runtime_error& e) {
      throw SceneError(e.what());
    }
  }
  return set;
}

collision::ShapeSet readCollisionGeometryFile(const std::string& path) {
  return readCollisionGeometryString(readTextFile(path), path);
}

std::string builtinCollisionGeometry(const std::string& model) { return collision::findGeometryFile(model); }

}  // namespace mrqp::scene
