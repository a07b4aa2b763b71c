// Distance and witness points of two convex shapes: GJK on the cores, libccd's MPR for overlapping
// cores and the margin tests; see distance.hpp.
#include "collision/distance.hpp"

#include <ccd/ccd.h>
#include <Eigen/LU>

#include <array>
#include <cmath>
#include <limits>

namespace mrqp::collision {

namespace {

// ---- libccd's view of a placed shape: the whole shape inflated by `inflate` ----
struct CcdObject {
  const PlacedShape* shape;
  double inflate;
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const Eigen::Vector3d d(dir->v[0], dir->v[1], dir->v[2]);
  Eigen::Vector3d s = o->shape->coreSupport(d);
  const double n = d.norm();
  const double r = o->shape->shape->radius + o->inflate;
  if (n > 0.0 && r > 0.0) s += (r / n) * d;
  out->v[0] = s.x();
  out->v[1] = s.y();
  out->v[2] = s.z();
}

void ccdCentre(const void* obj, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const Eigen::Vector3d c = o->shape->R * o->shape->shape->centre + o->shape->p;
  out->v[0] = c.x();
  out->v[1] = c.y();
  out->v[2] = c.z();
}

ccd_t ccdSettings() {
  ccd_t c;
  c.first_dir = ccdFirstDirDefault;
  c.support1 = ccdSupport;
  c.support2 = ccdSupport;
  c.center1 = ccdCentre;
  c.center2 = ccdCentre;
  c.max_iterations = 200;
  c.epa_tolerance = 1e-9;
  c.mpr_tolerance = 1e-10;
  c.dist_tolerance = 1e-10;
  return c;
}

Eigen::Vector3d worldCentre(const PlacedShape& s) { return s.R * s.shape->centre + s.p; }

// ---- GJK on the cores ----
struct Vertex {
  // w = b − a: a point of the Minkowski difference core_B − core_A
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double lambda = 1.0;  // barycentric weight in the simplex's closest point
};

struct Simplex {
  std::array<Vertex, 4> v;
  int n = 0;
};

// The closest point to the origin of the simplex's hull: over every face (subset of vertices)
// whose affine projection of the origin has non-negative barycentric coordinates, the one nearest
// the origin. The simplex is reduced to that face; v, a, b are the closest point and its witnesses.
void closestOnSimplex(Simplex& s, Eigen::Vector3d* v, Eigen::Vector3d* a, Eigen::Vector3d* b) noexcept {
  double best = std::numeric_limits<double>::infinity();
  int best_mask = 1;
  std::array<double, 4> best_lambda{1.0, 0.0, 0.0, 0.0};
  for (int mask = 1; mask < (1 << s.n); ++mask) {
    std::array<int, 4> idx{};
    int k = 0;
    for (int i = 0; i < s.n; ++i) {
      if ((mask >> i) & 1) idx[static_cast<std::size_t>(k++)] = i;
    }
    const Eigen::Vector3d& w0 = s.v[static_cast<std::size_t>(idx[0])].w;
    std::array<double, 4> lambda{1.0, 0.0, 0.0, 0.0};
    if (k > 1) {
      // min ‖w0 + Σ μj Ej‖², Ej = w_j − w0: G μ = −Eᵀ w0 with G = EᵀE.
      Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
      for (int j = 1; j < k; ++j)
        E.col(j - 1) = s.v[static_cast<std::size_t>(idx[static_cast<std::size_t>(j)])].w - w0;
      const int m = k - 1;
      Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
      Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
      G.topLeftCorner(m, m) = E.leftCols(m).transpose() * E.leftCols(m);
      rhs.head(m) = -(E.leftCols(m).transpose() * w0);
      const double scale = G.topLeftCorner(m, m).diagonal().maxCoeff();
      const double det = G.determinant();                           // the identity fills the unused corner
      if (!(std::abs(det) > 1e-14 * std::pow(scale, m))) continue;  // degenerate face
      const Eigen::Vector3d mu = G.inverse() * rhs;
      double sum = 0.0;
      bool inside = true;
      for (int j = 0; j < m; ++j) {
        lambda[static_cast<std::size_t>(j + 1)] = mu(j);
        sum += mu(j);
        if (mu(j) < 0.0) inside = false;
      }
      lambda[0] = 1.0 - sum;
      if (!inside || lambda[0] < 0.0) continue;
    }
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int j = 0; j < k; ++j)
      p += lambda[static_cast<std::size_t>(j)] *
           s.v[static_cast<std::size_t>(idx[static_cast<std::size_t>(j)])].w;
    const double d2 = p.squaredNorm();
    if (d2 < best) {
      best = d2;
      best_mask = mask;
      best_lambda = lambda;
    }
  }
  Simplex r;
  *v = Eigen::Vector3d::Zero();
  *a = Eigen::Vector3d::Zero();
  *b = Eigen::Vector3d::Zero();
  for (int i = 0; i < s.n; ++i) {
    if (!((best_mask >> i) & 1)) continue;
    const double l = best_lambda[static_cast<std::size_t>(r.n)];
    const Vertex& x = s.v[static_cast<std::size_t>(i)];
    *v += l * x.w;
    *a += l * x.a;
    *b += l * x.b;
    r.v[static_cast<std::size_t>(r.n)] = x;
    r.v[static_cast<std::size_t>(r.n++)].lambda = l;
  }
  s = r;
}

Vertex supportVertex(const PlacedShape& A, const PlacedShape& B, const Eigen::Vector3d& d) noexcept {
  Vertex x;  // minimises d·w over core_B − core_A
  x.a = A.coreSupport(d);
  x.b = B.coreSupport(-d);
  x.w = x.b - x.a;
  return x;
}

bool penetration(const PlacedShape& A, const PlacedShape& B, DistanceResult* out) noexcept {
  CcdObject oa{&A, 0.0}, ob{&B, 0.0};
  const ccd_t c = ccdSettings();
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir, pos;
  out->penetrating = true;
  out->simplex_size = 0;
  if (ccdMPRPenetration(&oa, &ob, &c, &depth, &dir, &pos) != 0) {
    out->distance = 0.0;
    const Eigen::Vector3d d = worldCentre(B) - worldCentre(A);
    out->normal = d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitZ();
    out->a = worldCentre(A);
    out->b = worldCentre(B);
    return false;
  }
  const Eigen::Vector3d n(dir.v[0], dir.v[1], dir.v[2]);
  const Eigen::Vector3d p(pos.v[0], pos.v[1], pos.v[2]);
  out->distance = -depth;
  out->normal = n;
  out->a = p + 0.5 * depth * n;
  out->b = p - 0.5 * depth * n;
  return true;
}

}  // namespace

bool distance(const PlacedShape& A, const PlacedShape& B, DistanceResult* out) noexcept {
  Eigen::Vector3d d = worldCentre(B) - worldCentre(A);
  if (!(d.squaredNorm() > 0.0)) d = Eigen::Vector3d::UnitX();
  Simplex s;
  s.v[0] = supportVertex(A, B, -d);
  s.n = 1;
  Eigen::Vector3d v = s.v[0].w, a = s.v[0].a, b = s.v[0].b;
  Simplex at_v = s;  // the simplex whose closest point is v
  const double scale = 1.0 + A.shape->boundingRadius() + B.shape->boundingRadius() + d.norm();
  const double tiny = 1e-24 * scale * scale;
  out->penetrating = false;
  int it = 0;
  for (; it < 64; ++it) {
    const double vv = v.squaredNorm();
    if (vv <= tiny) return penetration(A, B, out);
    const Vertex x = supportVertex(A, B, v);
    if (vv - v.dot(x.w) <= 1e-13 * vv) break;  // the lower bound v·w/‖v‖ meets ‖v‖
    bool known = false;
    for (int i = 0; i < s.n; ++i)
      known = known || (s.v[static_cast<std::size_t>(i)].w - x.w).squaredNorm() <= tiny;
    if (known || s.n == 4) break;
    s.v[static_cast<std::size_t>(s.n++)] = x;
    Eigen::Vector3d vn, an, bn;
    closestOnSimplex(s, &vn, &an, &bn);
    if (s.n == 4) return penetration(A, B, out);  // the origin is inside a tetrahedron
    if (vn.squaredNorm() >= vv) break;            // no progress: v is the answer
    v = vn;
    a = an;
    b = bn;
    at_v = s;
  }
  out->iterations = it;
  const double dc = v.norm();
  if (dc * dc <= tiny) return penetration(A, B, out);
  const Eigen::Vector3d n = v / dc;  // v = b − a
  const double ra = A.shape->radius, rb = B.shape->radius;
  out->normal = n;
  out->a = a + ra * n;
  out->b = b - rb * n;
  out->distance = dc - ra - rb;
  out->simplex_size = at_v.n <= 3 ? at_v.n : 0;
  for (int i = 0; i < out->simplex_size; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    out->simplex_a[ui] = at_v.v[ui].a;
    out->simplex_b[ui] = at_v.v[ui].b;
    out->simplex_lambda[ui] = at_v.v[ui].lambda;
  }
  return true;
}

bool closerThan(const PlacedShape& A, const PlacedShape& B, double delta) noexcept {
  CcdObject oa{&A, 0.5 * delta}, ob{&B, 0.5 * delta};
  const ccd_t c = ccdSettings();
  return ccdMPRIntersect(&oa, &ob, &c) != 0;
}

bool marginDistance(const PlacedShape& A, const PlacedShape& B, double margin, DistanceResult* out) noexcept {
  CcdObject oa{&A, margin}, ob{&B, margin};
  const ccd_t c = ccdSettings();
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir, pos;
  out->penetrating = false;
  if (ccdMPRPenetration(&oa, &ob, &c, &depth, &dir, &pos) != 0) {
    out->distance = std::numeric_limits<double>::infinity();
    return false;
  }
  const Eigen::Vector3d n(dir.v[0], dir.v[1], dir.v[2]);
  const Eigen::Vector3d p(pos.v[0], pos.v[1], pos.v[2]);
  out->distance = 2.0 * margin - depth;
  out->normal = n;
  out->a = p + (0.5 * depth - margin) * n;
  out->b = p - (0.5 * depth - margin) * n;
  return true;
}

}  // namespace mrqp::collision
