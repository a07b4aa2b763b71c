// Quickhull in 3-D with exact orientation tests.
//
// Which faces a new point sees is decided by the exact sign of the orientation
// determinant (a floating-point filter, then exact expansion arithmetic when the filter is
// inconclusive), so every step keeps the triangulated surface exactly convex and closed,
// whatever the rounding. The tolerance only decides which points are worth adding: a point
// within tol of the current hull is considered inside. Vertices that end up inside a hull
// facet or edge are removed afterwards (exact test), by rebuilding from the corners.
#include "convex_hull.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <utility>

namespace mrqp::gen {
namespace {

using Vec3 = Eigen::Vector3d;

// Fixed-order arithmetic for every rounded quantity that steers a decision: Eigen may
// vectorise reductions differently from one build to another, and the hull of given points
// must not depend on how the library was compiled.
double dot3(const Vec3& a, const Vec3& b) { return a.x() * b.x() + a.y() * b.y() + a.z() * b.z(); }
Vec3 cross3(const Vec3& a, const Vec3& b) {
  return Vec3(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}
double norm3(const Vec3& a) { return std::sqrt(dot3(a, a)); }

// ---- exact orientation ----------------------------------------------------------------

// s + e == a + b exactly (round to nearest, no overflow).
void twoSum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

// p + e == a * b exactly (no overflow or underflow).
void twoProduct(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

// A sum of doubles held exactly as non-overlapping components of increasing magnitude
// (Shewchuk's expansions). Holds up to kMax components, enough for the sums below.
class Expansion {
 public:
  void add(double b) {
    double q = b;
    std::size_t k = 0;
    for (std::size_t j = 0; j < size_; ++j) {
      double s = 0.0;
      double e = 0.0;
      twoSum(q, parts_[j], s, e);
      if (e != 0.0) parts_[k++] = e;
      q = s;
    }
    size_ = k;
    if (q != 0.0) parts_[size_++] = q;
  }

  // Adds sign * a * b * c exactly.
  void addProduct(double sign, double a, double b, double c) {
    double h = 0.0;
    double l = 0.0;
    twoProduct(a, b, h, l);
    double p = 0.0;
    double e = 0.0;
    twoProduct(h, c, p, e);
    add(sign * e);
    add(sign * p);
    if (l != 0.0) {
      twoProduct(l, c, p, e);
      add(sign * e);
      add(sign * p);
    }
  }

  // The largest component dominates the sum of the others.
  int sign() const { return size_ == 0 ? 0 : (parts_[size_ - 1] > 0.0 ? 1 : -1); }

 private:
  static constexpr std::size_t kMax = 100;  // at most 96 components are ever added
  std::array<double, kMax> parts_{};
  std::size_t size_ = 0;
};

// Exactly adds sign * det[p; q; r] (rows).
void addDeterminant(Expansion& x, double sign, const Vec3& p, const Vec3& q, const Vec3& r) {
  x.addProduct(sign, p.x(), q.y(), r.z());
  x.addProduct(-sign, p.x(), q.z(), r.y());
  x.addProduct(-sign, p.y(), q.x(), r.z());
  x.addProduct(sign, p.y(), q.z(), r.x());
  x.addProduct(sign, p.z(), q.x(), r.y());
  x.addProduct(-sign, p.z(), q.y(), r.x());
}

// Whether b - a was computed without rounding, component-wise.
bool exactDifference(const Vec3& a, const Vec3& b, const Vec3& diff) {
  for (int k = 0; k < 3; ++k) {
    double s = 0.0;
    double e = 0.0;
    twoSum(b[k], -a[k], s, e);
    if (e != 0.0 || s != diff[k]) return false;
  }
  return true;
}

// Sign of det[b - a; c - a; d - a] = ((b - a) x (c - a)) . (d - a): positive when d is
// above the plane of the counter-clockwise triangle (a, b, c).
int orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 w = d - a;
  const double vw0 = v.y() * w.z();
  const double vw1 = v.z() * w.y();
  const double vw2 = v.z() * w.x();
  const double vw3 = v.x() * w.z();
  const double vw4 = v.x() * w.y();
  const double vw5 = v.y() * w.x();
  const double det = u.x() * (vw0 - vw1) + u.y() * (vw2 - vw3) + u.z() * (vw4 - vw5);
  const double permanent = std::abs(u.x()) * (std::abs(vw0) + std::abs(vw1)) +
                           std::abs(u.y()) * (std::abs(vw2) + std::abs(vw3)) +
                           std::abs(u.z()) * (std::abs(vw4) + std::abs(vw5));
  // The rounding error of `det` is below 8 * 2^-53 * permanent; 1e-14 is ample.
  const double bound = 1e-14 * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  if (!std::isfinite(permanent) || permanent > 1e250) return det > 0.0 ? 1 : (det < 0.0 ? -1 : 0);
  Expansion x;
  if (exactDifference(a, b, u) && exactDifference(a, c, v) && exactDifference(a, d, w)) {
    addDeterminant(x, 1.0, u, v, w);  // common for nearby points: 6 products
  } else {
    // det[b - a; c - a; d - a] = D(b,c,d) - D(a,c,d) + D(a,b,d) - D(a,b,c): 24 products.
    addDeterminant(x, 1.0, b, c, d);
    addDeterminant(x, -1.0, a, c, d);
    addDeterminant(x, 1.0, a, b, d);
    addDeterminant(x, -1.0, a, b, c);
  }
  return x.sign();
}

// p * q - r * s with about one rounding error.
double differenceOfProducts(double p, double q, double r, double s) {
  const double rs = r * s;
  const double err = std::fma(r, s, -rs);
  return std::fma(p, q, -rs) - err;
}

// Accurate (b - a) x (c - a), the differences taken exactly as hi + lo pairs.
Vec3 accurateNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 uh;
  Vec3 ul;
  Vec3 vh;
  Vec3 vl;
  for (int k = 0; k < 3; ++k) {
    twoSum(b[k], -a[k], uh[k], ul[k]);
    twoSum(c[k], -a[k], vh[k], vl[k]);
  }
  Vec3 n;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    n[k] = differenceOfProducts(uh[i], vh[j], uh[j], vh[i]) +
           ((uh[i] * vl[j] + ul[i] * vh[j]) - (uh[j] * vl[i] + ul[j] * vh[i]));
  }
  return n;
}

// ---- quickhull ------------------------------------------------------------------------

struct Face {
  std::array<int, 3> v{};             // counter-clockwise seen from outside
  std::array<int, 3> nb{-1, -1, -1};  // nb[i]: the face across edge v[i] -> v[(i + 1) % 3]
  Vec3 n = Vec3::Zero();              // unit outward normal (for distances only)
  std::vector<int> outside;           // points outside the hull above this face
  bool alive = true;
  unsigned visibleMark = 0;
  unsigned hiddenMark = 0;
};

struct HorizonEdge {
  int a = 0;
  int b = 0;
  int across = 0;      // the face on the other side, which stays
  int acrossEdge = 0;  // index of the edge b -> a in `across`
};

// Quickhull over an array of distinct points; indices refer to that array.
class Quickhull {
 public:
  // `extent`: the largest side of the points' bounding box.
  Quickhull(const std::vector<Vec3>& p, double tol, double extent)
      : p_(p), tol_(tol), distErr_(64.0 * std::numeric_limits<double>::epsilon() * extent) {}

  // Builds the hull from the tetrahedron `s` (not flat). With exact orientations a step
  // cannot fail; should one anyway (a defect), it returns false, or with `skipFailures`
  // drops that point and goes on.
  bool build(const std::array<int, 4>& s, bool skipFailures) {
    faces_.clear();
    const std::array<std::array<int, 3>, 4> tris{
        {{s[0], s[1], s[2]}, {s[0], s[1], s[3]}, {s[0], s[2], s[3]}, {s[1], s[2], s[3]}}};
    const std::array<int, 4> opposite{s[3], s[2], s[1], s[0]};
    for (std::size_t k = 0; k < 4; ++k) {
      std::array<int, 3> t = tris[k];
      const int o = orientation(pt(t[0]), pt(t[1]), pt(t[2]), pt(opposite[k]));
      if (o == 0) return false;
      if (o > 0) std::swap(t[1], t[2]);  // the opposite vertex must be below
      addFace(t);
    }
    std::map<std::pair<int, int>, int> edges;
    for (int f = 0; f < 4; ++f) {
      for (int e = 0; e < 3; ++e) edges[{vtx(f, e), vtx(f, e + 1)}] = f;
    }
    for (int f = 0; f < 4; ++f) {
      for (int e = 0; e < 3; ++e) {
        const auto it = edges.find({vtx(f, e + 1), vtx(f, e)});
        if (it == edges.end()) return false;
        face(f).nb[static_cast<std::size_t>(e)] = it->second;
      }
    }

    std::vector<int> candidates;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      if (i != s[0] && i != s[1] && i != s[2] && i != s[3]) candidates.push_back(i);
    }
    assignOutside(candidates, {0, 1, 2, 3});

    std::vector<int> work{0, 1, 2, 3};
    while (!work.empty()) {
      const int f = work.back();
      if (!face(f).alive || face(f).outside.empty()) {
        work.pop_back();
        continue;
      }
      std::vector<int>& out = face(f).outside;
      const auto far = std::max_element(out.begin(), out.end(),
                                        [&](int a, int b) { return distance(f, a) < distance(f, b); });
      const int eye = *far;
      if (orientation(pt(vtx(f, 0)), pt(vtx(f, 1)), pt(vtx(f, 2)), pt(eye)) <= 0) {
        out.erase(far);  // rounding beyond any sane bound; never seen, dropped to be safe
        continue;
      }
      std::vector<int> created;
      if (!addPoint(f, eye, created)) {
        if (!skipFailures) return false;
        out.erase(far);
        continue;
      }
      work.pop_back();
      for (const int g : created) {
        if (!face(g).outside.empty()) work.push_back(g);
      }
    }
    return true;
  }

  // The live faces, reindexed to the points they use (in increasing index order).
  ConvexHull result() const {
    std::vector<int> used;
    for (const Face& f : faces_) {
      if (f.alive) used.insert(used.end(), f.v.begin(), f.v.end());
    }
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<int> remap(p_.size(), -1);
    ConvexHull hull;
    for (const int i : used) {
      remap[static_cast<std::size_t>(i)] = static_cast<int>(hull.vertices.size());
      hull.vertices.push_back(pt(i));
    }
    for (const Face& f : faces_) {
      if (!f.alive) continue;
      hull.faces.push_back({remap[static_cast<std::size_t>(f.v[0])], remap[static_cast<std::size_t>(f.v[1])],
                            remap[static_cast<std::size_t>(f.v[2])]});
    }
    return hull;
  }

 private:
  Face& face(int f) { return faces_[static_cast<std::size_t>(f)]; }
  const Face& face(int f) const { return faces_[static_cast<std::size_t>(f)]; }
  int vtx(int f, int e) const { return face(f).v[static_cast<std::size_t>(e % 3)]; }
  const Vec3& pt(int i) const { return p_[static_cast<std::size_t>(i)]; }
  double distance(int f, int i) const { return dot3(face(f).n, pt(i) - pt(face(f).v[0])); }

  void addFace(const std::array<int, 3>& v) {
    Face f;
    f.v = v;
    const Vec3 n = accurateNormal(pt(v[0]), pt(v[1]), pt(v[2]));
    const double len = norm3(n);
    // Never zero for a face whose plane misses a point (exact orientation), barring underflow.
    f.n = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
    faces_.push_back(std::move(f));
  }

  // Gives each point that is outside the faces `targets` to one of them, and drops the
  // others as inside. A point is outside when it is more than tol above a face plane, or
  // exactly above a face and more than tol from that face's triangle: next to nearly flat
  // parts of the hull a point can be barely above a face plane yet far from the hull.
  void assignOutside(const std::vector<int>& points, const std::vector<int>& targets) {
    for (const int i : points) {
      int best = -1;
      double bestDist = -std::numeric_limits<double>::infinity();
      for (const int f : targets) {
        const double dist = distance(f, i);
        if (dist > bestDist) {
          bestDist = dist;
          best = f;
        }
      }
      if (best < 0) continue;
      if (bestDist > tol_) {
        face(best).outside.push_back(i);
        continue;
      }
      int above = -1;
      double aboveDist = -std::numeric_limits<double>::infinity();
      bool near = false;
      for (const int f : targets) {
        const double dist = distance(f, i);
        if (dist < -distErr_) continue;  // below, whatever the rounding
        const Face& fc = face(f);
        if (orientation(pt(fc.v[0]), pt(fc.v[1]), pt(fc.v[2]), pt(i)) <= 0) continue;
        if (triangleDistance(f, i) <= tol_) {
          near = true;  // within tol of the hull
          break;
        }
        if (dist > aboveDist) {
          aboveDist = dist;
          above = f;
        }
      }
      if (!near && above >= 0) face(above).outside.push_back(i);
    }
  }

  // Distance from point i to the triangle of face f.
  double triangleDistance(int f, int i) const {
    const Face& fc = face(f);
    const Vec3& p = pt(i);
    bool over = true;
    double edge = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 3; ++e) {
      const Vec3& a = pt(fc.v[static_cast<std::size_t>(e)]);
      const Vec3& b = pt(fc.v[static_cast<std::size_t>((e + 1) % 3)]);
      const Vec3 ab = b - a;
      if (dot3(cross3(ab, p - a), fc.n) < 0.0) over = false;
      const double t = std::clamp(dot3(ab, p - a) / dot3(ab, ab), 0.0, 1.0);
      edge = std::min(edge, norm3(p - (a + t * ab)));
    }
    return over ? std::abs(distance(f, i)) : edge;
  }

  // Adds point `eye`, strictly above face `start`. On failure nothing is changed.
  bool addPoint(int start, int eye, std::vector<int>& created) {
    ++mark_;
    std::vector<int> visible{start};
    face(start).visibleMark = mark_;
    for (std::size_t k = 0; k < visible.size(); ++k) {
      for (const int g : face(visible[k]).nb) {
        if (g < 0 || !face(g).alive) return false;
        Face& fg = face(g);
        if (fg.visibleMark == mark_ || fg.hiddenMark == mark_) continue;
        if (orientation(pt(fg.v[0]), pt(fg.v[1]), pt(fg.v[2]), pt(eye)) > 0) {
          fg.visibleMark = mark_;
          visible.push_back(g);
        } else {
          fg.hiddenMark = mark_;
        }
      }
    }

    // The horizon: edges between replaced and kept faces; one simple closed loop.
    std::vector<HorizonEdge> horizon;
    for (const int f : visible) {
      for (int e = 0; e < 3; ++e) {
        const int g = face(f).nb[static_cast<std::size_t>(e)];
        if (face(g).visibleMark == mark_) continue;
        HorizonEdge h;
        h.a = vtx(f, e);
        h.b = vtx(f, e + 1);
        h.across = g;
        h.acrossEdge = -1;
        for (int ge = 0; ge < 3; ++ge) {
          if (vtx(g, ge) == h.b && vtx(g, ge + 1) == h.a) h.acrossEdge = ge;
        }
        if (h.acrossEdge < 0) return false;
        horizon.push_back(h);
      }
    }
    if (horizon.size() < 3) return false;
    std::map<int, std::size_t> byStart;
    for (std::size_t k = 0; k < horizon.size(); ++k) {
      if (!byStart.emplace(horizon[k].a, k).second) return false;
    }
    std::vector<HorizonEdge> loop;
    loop.reserve(horizon.size());
    std::size_t k = 0;
    do {
      loop.push_back(horizon[k]);
      const auto it = byStart.find(horizon[k].b);
      if (it == byStart.end()) return false;
      k = it->second;
    } while (k != 0 && loop.size() <= horizon.size());
    if (k != 0 || loop.size() != horizon.size()) return false;

    // New faces (a, b, eye), one per horizon edge, in loop order, linked to each other
    // and to the kept faces.
    const int firstNew = static_cast<int>(faces_.size());
    const int m = static_cast<int>(loop.size());
    for (const HorizonEdge& h : loop) addFace({h.a, h.b, eye});
    for (int i = 0; i < m; ++i) {
      const int f = firstNew + i;
      const HorizonEdge& h = loop[static_cast<std::size_t>(i)];
      face(f).nb = {h.across, firstNew + (i + 1) % m, firstNew + (i + m - 1) % m};
      face(h.across).nb[static_cast<std::size_t>(h.acrossEdge)] = f;
      created.push_back(f);
    }

    // Retire the replaced faces; their other outside points go to the new faces or, if
    // above none of them by more than tol, are inside.
    std::vector<int> orphans;
    for (const int f : visible) {
      Face& fv = face(f);
      fv.alive = false;
      for (const int i : fv.outside) {
        if (i != eye) orphans.push_back(i);
      }
      std::vector<int>().swap(fv.outside);
    }
    assignOutside(orphans, created);
    return true;
  }

  const std::vector<Vec3>& p_;
  double tol_;
  double distErr_;  // bound on the rounding error of distance()
  std::vector<Face> faces_;
  unsigned mark_ = 0;
};

double lineDistance(const Vec3& p, const Vec3& a, const Vec3& dir) {
  const Vec3 ap = p - a;
  return norm3(ap - dot3(ap, dir) * dir);
}

// Extreme points of points lying (within tol) in the plane through `origin` with unit
// normal `n`, in counter-clockwise order around n (Andrew's monotone chain).
std::vector<int> planarHull(const std::vector<Vec3>& p, const Vec3& origin, const Vec3& axisU, const Vec3& n,
                            double tol) {
  const Vec3 axisV = cross3(n, axisU);
  struct P2 {
    double x;
    double y;
    int i;
  };
  std::vector<P2> q;
  q.reserve(p.size());
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const Vec3 r = p[static_cast<std::size_t>(i)] - origin;
    q.push_back({dot3(r, axisU), dot3(r, axisV), i});
  }
  std::sort(q.begin(), q.end(), [](const P2& a, const P2& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.i < b.i)));
  });
  // Keeps c only if it is more than tol to the left of the line o -> a.
  auto leftTurn = [tol](const P2& o, const P2& a, const P2& c) {
    const double ex = a.x - o.x;
    const double ey = a.y - o.y;
    const double cross = ex * (c.y - o.y) - ey * (c.x - o.x);
    return cross > tol * std::hypot(ex, ey);
  };
  std::vector<P2> h(2 * q.size());
  std::size_t k = 0;
  for (const P2& c : q) {  // lower chain
    while (k >= 2 && !leftTurn(h[k - 2], h[k - 1], c)) --k;
    h[k++] = c;
  }
  const std::size_t lower = k + 1;
  for (std::size_t j = q.size() - 1; j-- > 0;) {  // upper chain
    while (k >= lower && !leftTurn(h[k - 2], h[k - 1], q[j])) --k;
    h[k++] = q[j];
  }
  h.resize(k > 1 ? k - 1 : k);  // the last point repeats the first
  // Points within tol of each other after projection are a single vertex.
  std::vector<int> out;
  for (const P2& c : h) {
    const bool dup = std::any_of(out.begin(), out.end(), [&](int i) {
      return norm3(p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(c.i)]) <= tol;
    });
    if (!dup) out.push_back(c.i);
  }
  return out;
}

ConvexHull hullOfDistinct(const std::vector<Vec3>& p, double tol, double extent) {
  ConvexHull hull;
  if (p.empty()) return hull;
  const int n = static_cast<int>(p.size());
  auto P = [&](int i) -> const Vec3& { return p[static_cast<std::size_t>(i)]; };

  // Initial simplex. The two farthest apart of the six axis-extreme points...
  std::array<int, 6> ext{};
  for (int axis = 0; axis < 3; ++axis) {
    int mn = 0;
    int mx = 0;
    for (int i = 1; i < n; ++i) {
      if (P(i)[axis] < P(mn)[axis]) mn = i;
      if (P(i)[axis] > P(mx)[axis]) mx = i;
    }
    ext[static_cast<std::size_t>(2 * axis)] = mn;
    ext[static_cast<std::size_t>(2 * axis + 1)] = mx;
  }
  int i0 = 0;
  int i1 = 0;
  double best = -1.0;
  for (const int a : ext) {
    for (const int b : ext) {
      const double d = dot3(P(a) - P(b), P(a) - P(b));
      if (d > best) {
        best = d;
        i0 = std::min(a, b);
        i1 = std::max(a, b);
      }
    }
  }
  if (std::sqrt(best) <= tol) {  // a single point
    hull.vertices.push_back(P(0));
    return hull;
  }
  const Vec3 dir = (P(i1) - P(i0)) / norm3(P(i1) - P(i0));
  // ...then the point farthest from their line...
  int i2 = -1;
  best = tol;
  for (int i = 0; i < n; ++i) {
    const double d = lineDistance(P(i), P(i0), dir);
    if (d > best) {
      best = d;
      i2 = i;
    }
  }
  if (i2 < 0) {  // collinear: the extremes along the line
    int mn = 0;
    int mx = 0;
    for (int i = 1; i < n; ++i) {
      if (dot3(P(i), dir) < dot3(P(mn), dir)) mn = i;
      if (dot3(P(i), dir) > dot3(P(mx), dir)) mx = i;
    }
    hull.vertices = {P(std::min(mn, mx)), P(std::max(mn, mx))};
    return hull;
  }
  // ...and the point farthest from their plane.
  const Vec3 n012 = accurateNormal(P(i0), P(i1), P(i2));
  const Vec3 normal = n012 / norm3(n012);
  int i3 = -1;
  best = tol;
  for (int i = 0; i < n; ++i) {
    const double d = std::abs(dot3(normal, P(i) - P(i0)));
    if (d > best) {
      best = d;
      i3 = i;
    }
  }
  if (i3 < 0) {  // coplanar: the planar hull's vertices
    for (const int i : planarHull(p, P(i0), dir, normal, tol)) hull.vertices.push_back(P(i));
    return hull;
  }

  Quickhull qh(p, tol, extent);
  if (qh.build({i0, i1, i2, i3}, false)) return qh.result();
  // Not expected (exact orientations keep every step consistent); be safe regardless.
  Quickhull fallback(p, tol, extent);
  fallback.build({i0, i1, i2, i3}, true);
  return fallback.result();
}

// For each vertex of a closed convex triangulated surface, whether it is a corner: its
// faces lie in at least three distinct planes (exact test). A vertex whose faces lie in
// one or two planes is inside a facet or an edge of the polytope.
std::vector<bool> extremeVertices(const ConvexHull& h) {
  const std::size_t nv = h.vertices.size();
  // Faces around each vertex, as offsets into one array.
  std::vector<std::size_t> start(nv + 1, 0);
  for (const auto& f : h.faces) {
    for (const int v : f) ++start[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::size_t> incident(start[nv]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t f = 0; f < h.faces.size(); ++f) {
    for (const int v : h.faces[f]) incident[fill[static_cast<std::size_t>(v)]++] = f;
  }
  auto vertex = [&](std::size_t f, std::size_t k) -> const Vec3& {
    return h.vertices[static_cast<std::size_t>(h.faces[f][k])];
  };
  // Whether face g lies in the plane of face f (their shared vertices trivially do).
  auto coplanar = [&](std::size_t f, std::size_t g) {
    const auto& fv = h.faces[f];
    for (std::size_t k = 0; k < 3; ++k) {
      if (std::find(fv.begin(), fv.end(), h.faces[g][k]) != fv.end()) continue;
      if (orientation(vertex(f, 0), vertex(f, 1), vertex(f, 2), vertex(g, k)) != 0) return false;
    }
    return true;
  };
  std::vector<bool> extreme(nv, false);
  for (std::size_t v = 0; v < nv; ++v) {
    std::array<std::size_t, 3> planes{};
    std::size_t count = 0;
    for (std::size_t k = start[v]; k < start[v + 1] && count < 3; ++k) {
      const std::size_t f = incident[k];
      bool known = false;
      for (std::size_t j = 0; j < count && !known; ++j) known = coplanar(planes[j], f);
      if (!known) planes[count++] = f;
    }
    extreme[v] = count >= 3;
  }
  return extreme;
}

}  // namespace

ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points, double eps) {
  // Distinct finite points, in order of first appearance.
  std::vector<int> order;
  order.reserve(points.size());
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    if (points[static_cast<std::size_t>(i)].allFinite()) order.push_back(i);
  }
  auto at = [&](int i) -> const Vec3& { return points[static_cast<std::size_t>(i)]; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const Vec3& x = at(a);
    const Vec3& y = at(b);
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  });
  order.erase(std::unique(order.begin(), order.end(), [&](int a, int b) { return at(a) == at(b); }),
              order.end());
  std::sort(order.begin(), order.end());
  std::vector<Vec3> p;
  p.reserve(order.size());
  for (const int i : order) p.push_back(at(i));

  if (p.empty()) return {};

  Vec3 lo = p[0];
  Vec3 hi = p[0];
  for (const Vec3& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double extent = (hi - lo).maxCoeff();
  const double eps0 = std::isfinite(eps) ? std::max(eps, 0.0) : 0.0;
  const double tol = std::max(eps0, 4.0 * std::numeric_limits<double>::epsilon()) * extent;

  ConvexHull hull = hullOfDistinct(p, tol, extent);
  if (hull.faces.empty()) return hull;
  // Quickhull keeps a point that became a vertex while outside even if later points put it
  // in the middle of a hull facet or edge. Such vertices are found exactly and the hull is
  // rebuilt from the extreme points alone (the same polytope).
  const std::vector<bool> extreme = extremeVertices(hull);
  if (std::all_of(extreme.begin(), extreme.end(), [](bool e) { return e; })) return hull;
  std::vector<Vec3> corners;
  for (std::size_t i = 0; i < extreme.size(); ++i) {
    if (extreme[i]) corners.push_back(hull.vertices[i]);
  }
  return hullOfDistinct(corners, tol, extent);
}

}  // namespace mrqp::gen
