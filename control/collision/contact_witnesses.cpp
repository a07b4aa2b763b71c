// Several witness pairs per pair of shapes at face or edge contact; see contact_witnesses.hpp.
#include "collision/contact_witnesses.hpp"

#include <algorithm>
#include <cstddef>

namespace mrqp::collision {

namespace {

constexpr int kMaxFeatureVertices = 8;
constexpr int kMaxFeatureEdges = 12;
/// Two witness pairs whose points are both this close (m) are one.
constexpr double kSameWitness = 1e-4;

/// The contact feature of a shape's core along a direction (shape frame): its vertices within the
/// band of the support plane, and the segments between them that lie in the core.
struct Feature {
  std::array<Eigen::Vector3d, kMaxFeatureVertices> vertex{};
  std::array<double, kMaxFeatureVertices> height{};
  std::array<int, kMaxFeatureVertices> id{};  ///< box: the corner's sign bits
  int nvertex = 0;
  std::array<std::array<int, 2>, kMaxFeatureEdges> edge{};
  int nedge = 0;
};

Eigen::Vector3d boxCorner(const Eigen::Vector3d& half, int bits) noexcept {
  return Eigen::Vector3d((bits & 1) != 0 ? half.x() : -half.x(), (bits & 2) != 0 ? half.y() : -half.y(),
                         (bits & 4) != 0 ? half.z() : -half.z());
}

/// Adds a vertex of height h to the feature, keeping the highest ones when it is full.
void offer(Feature& f, const Eigen::Vector3d& v, double h, int id) noexcept {
  int at = f.nvertex;
  if (f.nvertex == kMaxFeatureVertices) {
    at = 0;
    for (int i = 1; i < f.nvertex; ++i)
      if (f.height[static_cast<std::size_t>(i)] < f.height[static_cast<std::size_t>(at)]) at = i;
    if (f.height[static_cast<std::size_t>(at)] >= h) return;
  } else {
    ++f.nvertex;
  }
  const auto u = static_cast<std::size_t>(at);
  f.vertex[u] = v;
  f.height[u] = h;
  f.id[u] = id;
}

void addEdge(Feature& f, int i, int j) noexcept {
  if (f.nedge == kMaxFeatureEdges) return;
  f.edge[static_cast<std::size_t>(f.nedge++)] = {i, j};
}

/// The feature of `s`'s core in direction `d` (shape frame, unit).
Feature feature(const Shape& s, const Eigen::Vector3d& d, double band) noexcept {
  Feature f;
  const double top = d.dot(s.coreSupport(d));
  switch (s.kind) {
    case ShapeKind::Sphere:
      offer(f, Eigen::Vector3d::Zero(), 0.0, 0);
      break;
    case ShapeKind::Capsule:
      for (int i = 0; i < 2; ++i) {
        const Eigen::Vector3d v(0.0, 0.0, i == 0 ? -s.half.z() : s.half.z());
        if (d.dot(v) >= top - band) offer(f, v, d.dot(v), i);
      }
      if (f.nvertex == 2) addEdge(f, 0, 1);
      break;
    case ShapeKind::Box:
      for (int bits = 0; bits < 8; ++bits) {
        const Eigen::Vector3d v = boxCorner(s.half, bits);
        if (d.dot(v) >= top - band) offer(f, v, d.dot(v), bits);
      }
      // The box's edges join corners whose sign bits differ in one place.
      for (int i = 0; i < f.nvertex; ++i) {
        for (int j = i + 1; j < f.nvertex; ++j) {
          const int x = f.id[static_cast<std::size_t>(i)] ^ f.id[static_cast<std::size_t>(j)];
          if (x == 1 || x == 2 || x == 4) addEdge(f, i, j);
        }
      }
      break;
    case ShapeKind::Hull:
      for (int i = 0; i < s.nvertices; ++i) {
        const double h = d.dot(s.vertices[i]);
        if (h >= top - band) offer(f, s.vertices[i], h, i);
      }
      // Without the hull's faces: every segment between up to 4 feature vertices (inside the hull).
      if (f.nvertex <= 4) {
        for (int i = 0; i < f.nvertex; ++i)
          for (int j = i + 1; j < f.nvertex; ++j) addEdge(f, i, j);
      }
      break;
  }
  return f;
}

ShapePart vertexPart(const Feature& f, int i) noexcept {
  ShapePart p;
  p.count = 1;
  p.points[0] = f.vertex[static_cast<std::size_t>(i)];
  return p;
}

ShapePart edgePart(const Feature& f, int e) noexcept {
  ShapePart p;
  p.count = 2;
  const auto& ij = f.edge[static_cast<std::size_t>(e)];
  p.points[0] = f.vertex[static_cast<std::size_t>(ij[0])];
  p.points[1] = f.vertex[static_cast<std::size_t>(ij[1])];
  return p;
}

/// Closest points of segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision Detection 5.1.9):
/// parameters s, t ∈ [0, 1] and the squared distance.
double segmentSegment(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& q2, double* s, double* t) noexcept {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double tiny = 1e-18;
  if (a <= tiny && e <= tiny) {
    *s = *t = 0.0;
  } else if (a <= tiny) {
    *s = 0.0;
    *t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= tiny) {
      *t = 0.0;
      *s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      *s = denom > tiny * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      *t = (b * *s + f) / e;
      if (*t < 0.0) {
        *t = 0.0;
        *s = std::clamp(-c / a, 0.0, 1.0);
      } else if (*t > 1.0) {
        *t = 1.0;
        *s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + *s * d1 - p2 - *t * d2).squaredNorm();
}

/// Distance from a world point to the core of a box, capsule or sphere in closed form; −1 for a hull
/// (no closed form: the caller measures it).
double pointToCore(const PlacedShape& S, const Eigen::Vector3d& x) noexcept {
  const Eigen::Vector3d l = S.R.transpose() * (x - S.p);
  const Shape& s = *S.shape;
  switch (s.kind) {
    case ShapeKind::Sphere:
      return l.norm();
    case ShapeKind::Capsule:
      return Eigen::Vector3d(l.x(), l.y(), std::max(0.0, std::abs(l.z()) - s.half.z())).norm();
    case ShapeKind::Box:
      return (l.cwiseAbs() - s.half).cwiseMax(0.0).norm();
    case ShapeKind::Hull:
      return -1.0;
  }
  return -1.0;
}

/// The shape of a part: a hull of its one or two points with the shape's radius.
Shape partShape(const Shape& s, const ShapePart& part) noexcept {
  Shape h;
  h.kind = ShapeKind::Hull;
  h.radius = s.radius;
  h.vertices = part.points.data();
  h.nvertices = part.count;
  h.centre = part.count == 2 ? Eigen::Vector3d(0.5 * (part.points[0] + part.points[1])) : part.points[0];
  return h;
}

/// Collects the witnesses within the band, nearest first, without repeats.
struct Collector {
  Witness* out;
  int capacity;
  int count;
  double limit;

  void consider(const PlacedShape& A, const ShapePart& pa, const PlacedShape& B, const ShapePart& pb) noexcept {
    DistanceResult r;
    if (!partDistance(A, pa, B, pb, &r) || r.penetrating || !(r.distance <= limit)) return;
    for (int i = 0; i < count; ++i) {
      const DistanceResult& o = out[i].result;
      if ((o.a - r.a).squaredNorm() <= kSameWitness * kSameWitness &&
          (o.b - r.b).squaredNorm() <= kSameWitness * kSameWitness)
        return;
    }
    int at = count;
    if (count == capacity) {
      if (!(r.distance < out[count - 1].result.distance)) return;
      at = count - 1;
    } else {
      ++count;
    }
    while (at > 1 && out[at - 1].result.distance > r.distance) {
      out[at] = out[at - 1];
      --at;
    }
    out[at].a = pa;
    out[at].b = pb;
    out[at].result = r;
  }
};

}  // namespace

bool partDistance(const PlacedShape& A, const ShapePart& pa, const PlacedShape& B, const ShapePart& pb,
                  DistanceResult* out) noexcept {
  const Shape sa = pa.count == 0 ? *A.shape : partShape(*A.shape, pa);
  const Shape sb = pb.count == 0 ? *B.shape : partShape(*B.shape, pb);
  PlacedShape a = A, b = B;
  a.shape = &sa;
  b.shape = &sb;
  return distance(a, b, out);
}

int contactWitnesses(const PlacedShape& A, const PlacedShape& B, const DistanceResult& nearest, double band,
                     Witness* out, int capacity) noexcept {
  if (capacity < 1) return 0;
  out[0].a = ShapePart{};
  out[0].b = ShapePart{};
  out[0].result = nearest;
  if (nearest.penetrating || capacity == 1) return 1;
  // The features facing each other: A's along n, B's along −n (each in its shape's frame).
  const Feature fa = feature(*A.shape, A.R.transpose() * nearest.normal, band);
  const Feature fb = feature(*B.shape, -(B.R.transpose() * nearest.normal), band);
  if (fa.nvertex <= 1 && fb.nvertex <= 1) return 1;  // vertex against vertex: unique
  Collector c{out, capacity, 1, nearest.distance + band};
  const ShapePart whole{};
  // Vertices: those farther than the band (closed form where the other shape has one) are skipped
  // before the part's distance is measured.
  const double ra = A.shape->radius, rb = B.shape->radius;
  for (int i = 0; i < fa.nvertex && fa.nvertex > 1; ++i) {
    const double d = pointToCore(B, A.R * fa.vertex[static_cast<std::size_t>(i)] + A.p);
    if (d < 0.0 || d - ra - rb <= c.limit) c.consider(A, vertexPart(fa, i), B, whole);
  }
  for (int i = 0; i < fb.nvertex && fb.nvertex > 1; ++i) {
    const double d = pointToCore(A, B.R * fb.vertex[static_cast<std::size_t>(i)] + B.p);
    if (d < 0.0 || d - ra - rb <= c.limit) c.consider(A, whole, B, vertexPart(fb, i));
  }
  // Edge pairs: only crossings count (closest points inside both edges; an end is a vertex above),
  // found in closed form first, then measured as parts (for the row's simplex).
  for (int i = 0; i < fa.nedge; ++i) {
    const ShapePart ea = edgePart(fa, i);
    const Eigen::Vector3d a0 = A.R * ea.points[0] + A.p, a1 = A.R * ea.points[1] + A.p;
    for (int j = 0; j < fb.nedge; ++j) {
      const ShapePart eb = edgePart(fb, j);
      double s = 0.0, t = 0.0;
      const double d2 = segmentSegment(a0, a1, B.R * eb.points[0] + B.p, B.R * eb.points[1] + B.p, &s, &t);
      const double reach = c.limit + ra + rb;
      if (s <= 0.0 || s >= 1.0 || t <= 0.0 || t >= 1.0 || d2 > reach * reach) continue;
      c.consider(A, ea, B, eb);
    }
  }
  return c.count;
}

}  // namespace mrqp::collision
