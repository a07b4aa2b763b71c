#include <catch2/catch.hpp>

#include "convex_hull.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>

using mrqp::gen::ConvexHull;
using mrqp::gen::convexHull;
using Vec3 = Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Volume enclosed by the faces, by the divergence theorem: sum over the triangles of
// a . (b x c) / 6 (positive when the faces are counter-clockwise seen from outside).
double volume(const ConvexHull& h) {
  double v = 0.0;
  for (const auto& f : h.faces) {
    const Vec3& a = h.vertices[static_cast<std::size_t>(f[0])];
    const Vec3& b = h.vertices[static_cast<std::size_t>(f[1])];
    const Vec3& c = h.vertices[static_cast<std::size_t>(f[2])];
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

Vec3 unitNormal(const ConvexHull& h, const std::array<int, 3>& f) {
  const Vec3& a = h.vertices[static_cast<std::size_t>(f[0])];
  const Vec3& b = h.vertices[static_cast<std::size_t>(f[1])];
  const Vec3& c = h.vertices[static_cast<std::size_t>(f[2])];
  return (b - a).cross(c - a).normalized();
}

// Closed, consistently oriented 2-manifold of genus 0: every directed edge appears once and
// its reverse once, the face indices are valid and distinct, every vertex is used, and
// V - E + F = 2.
void requireClosedSurface(const ConvexHull& h) {
  const int nv = static_cast<int>(h.vertices.size());
  std::map<std::pair<int, int>, int> directed;
  std::set<int> used;
  for (const auto& f : h.faces) {
    for (int k = 0; k < 3; ++k) {
      REQUIRE(f[static_cast<std::size_t>(k)] >= 0);
      REQUIRE(f[static_cast<std::size_t>(k)] < nv);
      used.insert(f[static_cast<std::size_t>(k)]);
    }
    REQUIRE(f[0] != f[1]);
    REQUIRE(f[1] != f[2]);
    REQUIRE(f[2] != f[0]);
    for (int k = 0; k < 3; ++k) {
      ++directed[{f[static_cast<std::size_t>(k)], f[static_cast<std::size_t>((k + 1) % 3)]}];
    }
  }
  REQUIRE(static_cast<int>(used.size()) == nv);
  for (const auto& [edge, count] : directed) {
    REQUIRE(count == 1);
    const auto rev = directed.find({edge.second, edge.first});
    REQUIRE(rev != directed.end());
    REQUIRE(rev->second == 1);
  }
  const long long v = nv;
  const long long e = static_cast<long long>(directed.size()) / 2;
  const long long f = static_cast<long long>(h.faces.size());
  REQUIRE(v - e + f == 2);
}

// Every point lies on the inner side of every face plane, up to `tol`.
void requireContains(const ConvexHull& h, const std::vector<Vec3>& points, double tol) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const auto& f : h.faces) {
    const Vec3 n = unitNormal(h, f);
    const Vec3& a = h.vertices[static_cast<std::size_t>(f[0])];
    for (const Vec3& p : points) worst = std::max(worst, n.dot(p - a));
  }
  INFO("largest distance outside a face plane: " << worst);
  REQUIRE(worst <= tol);
}

// Each vertex is one of the input points.
void requireVerticesFromInput(const ConvexHull& h, const std::vector<Vec3>& points) {
  for (const Vec3& v : h.vertices) {
    REQUIRE(std::find(points.begin(), points.end(), v) != points.end());
  }
}

std::vector<Vec3> cubeCorners() {
  std::vector<Vec3> c;
  for (int i = 0; i < 8; ++i) c.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  return c;
}

std::vector<Vec3> sortedVertices(std::vector<Vec3> v) {
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return v;
}

// The nearest single-precision point, as stored in STL files. (Through volatile: GCC 12 at
// -O2 was seen to drop a double -> float -> double round trip.)
Vec3 roundedToFloat(const Vec3& p) {
  Vec3 q;
  for (int k = 0; k < 3; ++k) {
    volatile float f = static_cast<float>(p[k]);
    q[k] = f;
  }
  return q;
}

std::vector<Vec3> randomSphere(std::mt19937& rng, int n, double radius = 1.0,
                               const Vec3& centre = Vec3::Zero()) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> pts;
  while (static_cast<int>(pts.size()) < n) {
    const Vec3 p(g(rng), g(rng), g(rng));
    if (p.norm() > 1e-3) pts.push_back(centre + radius * p.normalized());
  }
  return pts;
}

}  // namespace

TEST_CASE("mesh hull: hull of a tetrahedron", "[mesh][hull]") {
  const std::vector<Vec3> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const ConvexHull h = convexHull(pts);
  REQUIRE(h.vertices == pts);  // all of them, in input order
  REQUIRE(h.faces.size() == 4);
  requireClosedSurface(h);
  REQUIRE(volume(h) == Approx(1.0 / 6.0).epsilon(1e-12));
}

TEST_CASE("mesh hull: hull of cube corners plus random interior points is the cube", "[mesh][hull]") {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> inside(0.001, 0.999);
  std::vector<Vec3> pts = cubeCorners();
  for (int i = 0; i < 2000; ++i) pts.emplace_back(inside(rng), inside(rng), inside(rng));
  std::shuffle(pts.begin(), pts.end(), rng);

  const ConvexHull h = convexHull(pts);
  REQUIRE(h.vertices.size() == 8);
  REQUIRE(sortedVertices(h.vertices) == sortedVertices(cubeCorners()));
  REQUIRE(h.faces.size() == 12);
  requireClosedSurface(h);
  REQUIRE(volume(h) == Approx(1.0).epsilon(1e-12));
  requireContains(h, pts, 1e-12);
  // Every face normal is one of the six axis directions, pointing away from the centre.
  for (const auto& f : h.faces) {
    const Vec3 n = unitNormal(h, f);
    REQUIRE(n.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-12));
    REQUIRE(n.dot(h.vertices[static_cast<std::size_t>(f[0])] - Vec3(0.5, 0.5, 0.5)) > 0.0);
  }
}

TEST_CASE("mesh hull: points on the cube's faces and edges and duplicates do not become vertices",
          "[mesh][hull]") {
  std::vector<Vec3> pts;
  const int n = 10;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        const bool surface = i == 0 || i == n || j == 0 || j == n || k == 0 || k == n;
        if (surface) pts.emplace_back(i / double(n), j / double(n), k / double(n));
      }
    }
  }
  const std::vector<Vec3> once = pts;
  pts.insert(pts.end(), once.begin(), once.end());  // every point twice
  std::mt19937 rng(7);
  std::shuffle(pts.begin(), pts.end(), rng);

  const ConvexHull h = convexHull(pts);
  REQUIRE(sortedVertices(h.vertices) == sortedVertices(cubeCorners()));
  REQUIRE(h.faces.size() == 12);
  requireClosedSurface(h);
  REQUIRE(volume(h) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("mesh hull: random points on a sphere are all inside or on the hull", "[mesh][hull]") {
  std::mt19937 rng(2024);
  const int n = GENERATE(50, 500, 3000);
  const std::vector<Vec3> pts = randomSphere(rng, n);
  const ConvexHull h = convexHull(pts);

  requireClosedSurface(h);
  requireVerticesFromInput(h, pts);
  requireContains(h, pts, 1e-9);
  // Points on a sphere are all extreme: every one is a vertex, and a triangulated
  // sphere has F = 2V - 4.
  REQUIRE(static_cast<int>(h.vertices.size()) == n);
  REQUIRE(h.faces.size() == 2 * h.vertices.size() - 4);
  const double ball = 4.0 / 3.0 * kPi;
  REQUIRE(volume(h) > 0.0);
  REQUIRE(volume(h) < ball);
  if (n >= 3000) REQUIRE(volume(h) > 0.99 * ball);
}

TEST_CASE("mesh hull: random points in a ball: the hull contains them all", "[mesh][hull]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> pts;
  while (pts.size() < 5000) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (p.norm() <= 1.0) pts.push_back(p);
  }
  const ConvexHull h = convexHull(pts);
  requireClosedSurface(h);
  requireVerticesFromInput(h, pts);
  requireContains(h, pts, 1e-9);
  REQUIRE(h.vertices.size() < pts.size());
}

TEST_CASE("mesh hull: the hull is idempotent", "[mesh][hull]") {
  std::mt19937 rng(5);
  std::vector<Vec3> pts = randomSphere(rng, 400, 0.3, Vec3(1, 2, 3));
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int i = 0; i < 400; ++i) pts.push_back(Vec3(1, 2, 3) + Vec3(u(rng), u(rng), u(rng)));
  std::vector<Vec3> cube = cubeCorners();
  for (Vec3& c : cube) c = 0.2 * c;
  pts.insert(pts.end(), cube.begin(), cube.end());

  const ConvexHull h1 = convexHull(pts);
  const ConvexHull h2 = convexHull(h1.vertices);
  REQUIRE(h2.vertices == h1.vertices);  // same vertices, same order
  REQUIRE(h2.faces.size() == h1.faces.size());
  REQUIRE(volume(h2) == Approx(volume(h1)).epsilon(1e-12));
  const ConvexHull h3 = convexHull(h2.vertices);
  REQUIRE(h3.vertices == h2.vertices);
  REQUIRE(h3.faces == h2.faces);
}

TEST_CASE("mesh hull: the hull is invariant under translation and scaling", "[mesh][hull]") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> inside(0.01, 0.99);
  std::vector<Vec3> pts = cubeCorners();
  for (int i = 0; i < 300; ++i) pts.emplace_back(inside(rng), inside(rng), inside(rng));
  for (const double scale : {1e-4, 1e3}) {
    std::vector<Vec3> moved;
    for (const Vec3& p : pts) moved.push_back(scale * p + Vec3(1e3, -2e3, 5e2));
    const ConvexHull h = convexHull(moved);
    REQUIRE(h.vertices.size() == 8);
    REQUIRE(h.faces.size() == 12);
    requireClosedSurface(h);
  }
}

TEST_CASE("mesh hull: float-rounded cylinders with many coplanar points give a valid hull", "[mesh][hull]") {
  // Like CAD meshes: two circles of 256 points in the planes z = 0 and z = h, rotated
  // and translated, coordinates rounded to float, plus the caps' centres and points
  // along the side lines.
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(1.1, Vec3::UnitZ())).toRotationMatrix();
  const Vec3 t(0.12, -0.4, 0.9);
  std::vector<Vec3> pts;
  auto add = [&](const Vec3& p) { pts.push_back(roundedToFloat(r * p + t)); };
  const int m = 256;
  for (int i = 0; i < m; ++i) {
    const double a = 2.0 * kPi * i / m;
    for (const double z : {0.0, 0.05, 0.1, 0.15, 0.2}) add(Vec3(0.04 * std::cos(a), 0.04 * std::sin(a), z));
  }
  add(Vec3(0, 0, 0));
  add(Vec3(0, 0, 0.2));
  const ConvexHull h = convexHull(pts);
  requireClosedSurface(h);
  requireVerticesFromInput(h, pts);
  requireContains(h, pts, 1e-7);
  const double exact = kPi * 0.04 * 0.04 * 0.2;
  REQUIRE(volume(h) == Approx(exact).epsilon(1e-3));
  // A coarse tolerance (about 2 um here) gives a valid hull too, within that tolerance.
  const ConvexHull coarse = convexHull(pts, 1e-5);
  requireClosedSurface(coarse);
  requireVerticesFromInput(coarse, pts);
  requireContains(coarse, pts, 1e-5 * 0.2);
  REQUIRE(volume(coarse) == Approx(exact).epsilon(1e-3));
}

TEST_CASE("mesh hull: degenerate inputs", "[mesh][hull]") {
  SECTION("no points") {
    const ConvexHull h = convexHull({});
    REQUIRE(h.vertices.empty());
    REQUIRE(h.faces.empty());
  }
  SECTION("one point, repeated") {
    const ConvexHull h = convexHull({Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)});
    REQUIRE(h.vertices == std::vector<Vec3>{Vec3(1, 2, 3)});
    REQUIRE(h.faces.empty());
  }
  SECTION("two points") {
    const ConvexHull h = convexHull({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(0, 0, 0)});
    REQUIRE(h.vertices == std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 1, 1)});
    REQUIRE(h.faces.empty());
  }
  SECTION("collinear points: the two ends") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 a(1, -1, 2);
    const Vec3 d(0.3, 0.5, -0.2);
    std::vector<Vec3> pts;
    for (int i = 0; i < 100; ++i) pts.push_back(a + u(rng) * d);
    pts.insert(pts.begin() + 40, a + 1.5 * d);
    pts.insert(pts.begin() + 10, a - 0.5 * d);
    const ConvexHull h = convexHull(pts);
    REQUIRE(h.faces.empty());
    REQUIRE(h.vertices == std::vector<Vec3>{a - 0.5 * d, a + 1.5 * d});  // input order
  }
  SECTION("coplanar points: the polygon's corners") {
    // A tilted square grid with points inside and on the edges.
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    std::vector<Vec3> pts;
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) pts.push_back(r * Vec3(i / 8.0, j / 8.0, 0.0) + Vec3(5, 5, 5));
    }
    pts.push_back(pts[3]);
    const ConvexHull h = convexHull(pts);
    REQUIRE(h.faces.empty());
    REQUIRE(h.vertices.size() == 4);
    const std::vector<Vec3> corners{r * Vec3(0, 0, 0) + Vec3(5, 5, 5), r * Vec3(0, 1, 0) + Vec3(5, 5, 5),
                                    r * Vec3(1, 0, 0) + Vec3(5, 5, 5), r * Vec3(1, 1, 0) + Vec3(5, 5, 5)};
    for (const Vec3& c : corners) {
      REQUIRE(std::count(h.vertices.begin(), h.vertices.end(), c) == 1);
    }
    // Cyclic order: consecutive corners are the square's sides, not its diagonals.
    for (std::size_t k = 0; k < 4; ++k) {
      REQUIRE((h.vertices[k] - h.vertices[(k + 1) % 4]).norm() == Approx(1.0));
    }
  }
  SECTION("coplanar random points: a convex polygon") {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> pts;
    for (int i = 0; i < 500; ++i) pts.emplace_back(u(rng), u(rng), 2.0);
    const ConvexHull h = convexHull(pts);
    REQUIRE(h.faces.empty());
    REQUIRE(h.vertices.size() >= 3);
    requireVerticesFromInput(h, pts);
    // Every input point is on the inner side of every polygon edge (counter-clockwise
    // around +z or -z, consistently).
    const std::size_t m = h.vertices.size();
    double sign = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3 e = h.vertices[(k + 1) % m] - h.vertices[k];
      const Vec3 next = h.vertices[(k + 2) % m] - h.vertices[(k + 1) % m];
      const double turn = e.cross(next).z();
      REQUIRE(turn != 0.0);
      if (sign == 0.0) sign = turn;
      REQUIRE(turn * sign > 0.0);
      for (const Vec3& p : pts) REQUIRE(sign * e.cross(p - h.vertices[k]).z() >= -1e-12);
    }
  }
  SECTION("non-finite points are ignored") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<Vec3> pts{Vec3(nan, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0),
                          Vec3(0, inf, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    const ConvexHull h = convexHull(pts);
    REQUIRE(h.vertices.size() == 4);
    REQUIRE(h.faces.size() == 4);
    REQUIRE(volume(h) == Approx(1.0 / 6.0));
    REQUIRE(convexHull({Vec3(nan, nan, nan)}).vertices.empty());
  }
  SECTION("almost flat: points within tolerance of a plane are coplanar") {
    const ConvexHull flat = convexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 1e-12)});
    REQUIRE(flat.faces.empty());
    REQUIRE(flat.vertices.size() == 3);
    const ConvexHull solid = convexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 1e-6)});
    REQUIRE(solid.faces.size() == 4);
    REQUIRE(volume(solid) == Approx(1e-6 / 6.0));
  }
}
