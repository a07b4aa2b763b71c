// The generator's convex hulls of the JVRC-1 collision meshes (model_gen: COLLADA reader +
// quickhull, what `mrqp-gen --package-path` emits) against the hulls the upstream controllers use
// (jvrc_description/convex/jvrc1/<mesh>-ch.txt, qhull output). For each of the 35 meshes:
//   - every upstream hull vertex lies inside ours or within kInsideTol of it;
//   - the volumes agree within kVolumeRatio.
// The measured figures (worst vertex outside, volume ratios) are printed; docs/collision.md
// says where and why the hulls differ.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <dirent.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "hull_faces.hpp"
#include "mesh_reader.hpp"

namespace {

constexpr double kInsideTol = 1e-6;    // m: the upstream vertices are float32 values (about 1e-7 m apart)
constexpr double kVolumeRatio = 1e-4;  // |V_ours / V_upstream − 1|

struct QhullHull {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> facets;
};

QhullHull readQhull(const std::string& path) {
  std::ifstream f(path);
  QhullHull h;
  int dim = 0, np = 0, nf = 0, nr = 0;
  f >> dim >> np >> nf >> nr;
  REQUIRE(dim == 3);
  for (int i = 0; i < np; ++i) {
    Eigen::Vector3d p;
    f >> p.x() >> p.y() >> p.z();
    h.points.push_back(p);
  }
  for (int i = 0; i < nf; ++i) {
    int k = 0;
    f >> k;
    std::vector<int> face(static_cast<std::size_t>(k));
    for (int& v : face) f >> v;
    h.facets.push_back(face);
  }
  REQUIRE(f);
  return h;
}

// Volume of a convex polytope from its facets (fans from the centroid; orientation-free).
double facetVolume(const QhullHull& h, std::vector<Eigen::Vector3d>* vertices) {
  std::vector<int> used;
  for (const auto& f : h.facets) used.insert(used.end(), f.begin(), f.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i : used) {
    c += h.points[static_cast<std::size_t>(i)];
    vertices->push_back(h.points[static_cast<std::size_t>(i)]);
  }
  c /= static_cast<double>(used.size());
  double v = 0.0;
  for (const auto& f : h.facets) {
    const Eigen::Vector3d& a = h.points[static_cast<std::size_t>(f[0])];
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {
      const Eigen::Vector3d& b = h.points[static_cast<std::size_t>(f[k])];
      const Eigen::Vector3d& d = h.points[static_cast<std::size_t>(f[k + 1])];
      v += std::abs((a - c).dot((b - c).cross(d - c))) / 6.0;
    }
  }
  return v;
}

}  // namespace

TEST_CASE("collision: JVRC-1: the generator's mesh hulls hold the upstream hulls, volumes within 1e-4",
          "[collision][hull]") {
  const std::string dir = std::string(MRQP_SHARED_MODELS_DIR) + "/jvrc_description";
  std::vector<std::string> names;
  DIR* d = opendir((dir + "/convex/jvrc1").c_str());
  REQUIRE(d != nullptr);
  while (const dirent* e = readdir(d)) {
    const std::string n = e->d_name;
    if (n.size() > 7 && n.compare(n.size() - 7, 7, "-ch.txt") == 0)
      names.push_back(n.substr(0, n.size() - 7));
  }
  closedir(d);
  std::sort(names.begin(), names.end());
  REQUIRE(names.size() == 35);
  double worst_out = 0.0, worst_ratio = 0.0;
  std::string worst_out_mesh, worst_ratio_mesh;
  for (const std::string& n : names) {
    INFO(n);
    const mrqp::gen::MeshReadResult mesh = mrqp::gen::readMeshVertices(dir + "/meshes/" + n + ".dae");
    REQUIRE(mesh.ok);
    const mrqp::testing::HullFaces ours = mrqp::testing::hullFaces(mesh.vertices);
    REQUIRE(!ours.faces.empty());
    const QhullHull up = readQhull(dir + "/convex/jvrc1/" + n + "-ch.txt");
    std::vector<Eigen::Vector3d> up_vertices;
    const double vup = facetVolume(up, &up_vertices);
    double out = 0.0;
    for (const Eigen::Vector3d& v : up_vertices)
      out = std::max(out, mrqp::testing::pointHullDistance(ours, v));
    CHECK(out <= kInsideTol);
    const double ratio = mrqp::testing::hullVolume(ours) / vup;
    CHECK(std::abs(ratio - 1.0) <= kVolumeRatio);
    if (out > worst_out) {
      worst_out = out;
      worst_out_mesh = n;
    }
    if (std::abs(ratio - 1.0) > worst_ratio) {
      worst_ratio = std::abs(ratio - 1.0);
      worst_ratio_mesh = n;
    }
  }
  WARN("worst upstream vertex outside our hull: " << worst_out << " m (" << worst_out_mesh
                                                  << "); worst |volume ratio - 1|: " << worst_ratio << " ("
                                                  << worst_ratio_mesh << ")");
}
