#include "runtime_text.hpp"

namespace mrqp::gen {

// Storage conventions of the text below: Eigen 3×3 matrices are column-major, M(i, j) = m[i + 3 j];
// frame_R is row-major, Rf(i, j) = frame_R[f][3 i + j]; nv×k Eigen matrices are column-major.

const char* runtimeKernels() {
  return R"(/// The std::array position of a body or frame index (an int, >= 0 where it is used).
inline constexpr std::size_t ix(int i) noexcept { return static_cast<std::size_t>(i); }

/// out = R x (R column-major).
inline void rotate(const double* R, const double* x, double* out) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = R[i] * x[0] + R[i + 3] * x[1] + R[i + 6] * x[2];
}

/// out = Rᵀ x.
inline void rotateT(const double* R, const double* x, double* out) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
}

inline void cross(const double* a, const double* b, double* out) noexcept {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/// out = X m: a parent motion in child coordinates, (Eᵀ ω, Eᵀ (v + ω × r)).
inline void motionToChild(const double* E, const double* r, const double* m, double* out) noexcept {
  const double l[3] = {m[3] + m[1] * r[2] - m[2] * r[1], m[4] + m[2] * r[0] - m[0] * r[2],
                       m[5] + m[0] * r[1] - m[1] * r[0]};
  rotateT(E, m, out);
  rotateT(E, l, out + 3);
}

/// out += X* f: a child wrench in parent coordinates, (E n + r × E f, E f).
inline void forceToParent(const double* E, const double* r, const double* f, double* out) noexcept {
  double en[3], ef[3];
  rotate(E, f, en);
  rotate(E, f + 3, ef);
  out[0] += en[0] + r[1] * ef[2] - r[2] * ef[1];
  out[1] += en[1] + r[2] * ef[0] - r[0] * ef[2];
  out[2] += en[2] + r[0] * ef[1] - r[1] * ef[0];
  out[3] += ef[0];
  out[4] += ef[1];
  out[5] += ef[2];
}

/// World pose of a child: R = Rp Rl, p = pp + Rp pl.
inline void composePose(const double* Rp, const double* pp, const double* Rl, const double* pl, double* R,
                        double* p) noexcept {
  for (int j = 0; j < 3; ++j) rotate(Rp, Rl + 3 * j, R + 3 * j);
  rotate(Rp, pl, p);
  for (int i = 0; i < 3; ++i) p[i] += pp[i];
}

/// Body wrench I a + v ×* I v as a linear map of φ = (m, h, Ixx, Ixy, Iyy, Ixz, Iyz, Izz):
/// A is 6×10, row-major.
inline void bodyRegressor(const double* v, const double* a, double A[6][10]) noexcept {
  const double* w = v;
  const double* vl = v + 3;
  const double* al = a;      // angular acceleration
  const double* ll = a + 3;  // linear acceleration
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 10; ++k) A[i][k] = 0.0;
  double wxv[3];
  cross(w, vl, wxv);
  for (int i = 0; i < 3; ++i) A[3 + i][0] = ll[i] + wxv[i];
  // h columns: angular −[ll]× − [w]×[vl]× + [vl]×[w]× = −[ll]× − [w × vl]×; linear [al]× + [w]×[w]×
  const double c[3] = {ll[0] + wxv[0], ll[1] + wxv[1], ll[2] + wxv[2]};
  const double cx[3][3] = {{0.0, -c[2], c[1]}, {c[2], 0.0, -c[0]}, {-c[1], c[0], 0.0}};
  const double ax[3][3] = {{0.0, -al[2], al[1]}, {al[2], 0.0, -al[0]}, {-al[1], al[0], 0.0}};
  const double ww[3][3] = {{-(w[1] * w[1] + w[2] * w[2]), w[0] * w[1], w[0] * w[2]},
                           {w[0] * w[1], -(w[0] * w[0] + w[2] * w[2]), w[1] * w[2]},
                           {w[0] * w[2], w[1] * w[2], -(w[0] * w[0] + w[1] * w[1])}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      A[i][1 + j] = -cx[i][j];
      A[3 + i][1 + j] = ax[i][j] + ww[i][j];
    }
  // inertia columns: L(al) + [w]× L(w), L(x) = [[x0, x1, 0, x2, 0, 0], [0, x0, x1, 0, x2, 0], [0, 0, 0, x0, x1, x2]]
  const double Lw[3][6] = {{w[0], w[1], 0.0, w[2], 0.0, 0.0},
                           {0.0, w[0], w[1], 0.0, w[2], 0.0},
                           {0.0, 0.0, 0.0, w[0], w[1], w[2]}};
  const double La[3][6] = {{al[0], al[1], 0.0, al[2], 0.0, 0.0},
                           {0.0, al[0], al[1], 0.0, al[2], 0.0},
                           {0.0, 0.0, 0.0, al[0], al[1], al[2]}};
  for (int k = 0; k < 6; ++k) {
    const double col[3] = {Lw[0][k], Lw[1][k], Lw[2][k]};
    double wc[3];
    cross(w, col, wc);
    for (int i = 0; i < 3; ++i) A[i][4 + k] = La[i][k] + wc[i];
  }
}

)";
}

const char* runtimeChainWalks() {
  return R"(/// F (a wrench in body b's frame) walked up to the root: M(v_b, v_c) = g_b g_c S_cᵀ F for every
/// ancestor c with a joint; the free-flyer root takes the whole 6-vector.
inline void chainToRoot(const Data& d, int b, const double* F0, MassMatrix& M) noexcept {
  double* Mp = M.data();
  const int vi = vIndex[b];
  const double gi = gain[b];
  double F[6] = {F0[0], F0[1], F0[2], F0[3], F0[4], F0[5]};
  for (int c = b;;) {
    const int p = parentOf[c];
    if (p < 0 || (p == 0 && !floating_base)) break;
    double G[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    forceToParent(d.Rl[ix(c)].data(), d.pl[ix(c)].data(), F, G);
    for (int k = 0; k < 6; ++k) F[k] = G[k];
    c = p;
    if (c == 0) {
      for (int k = 0; k < 6; ++k) {
        Mp[k + nv * vi] += gi * F[k];
        Mp[vi + nv * k] += gi * F[k];
      }
      break;
    }
    double x = 0.0;
    for (int k = 0; k < 6; ++k) x += S6[c][k] * F[k];
    x *= gi * gain[c];
    Mp[vi + nv * vIndex[c]] += x;
    Mp[vIndex[c] + nv * vi] += x;
  }
}

/// Composite inertia of body b added to its parent p:
/// I_p += E I Eᵀ − (Eh rᵀ + r Ehᵀ) + 2 (r·Eh) 1 − m (r rᵀ − |r|² 1), h_p += Eh + m r, m_p += m.
inline void addCompositeToParent(Data& d, int b, int p) noexcept {
  const double* E = d.Rl[ix(b)].data();
  const double* r = d.pl[ix(b)].data();
  const double* I = d.cI[ix(b)].data();
  double* Ip = d.cI[ix(p)].data();
  const double m = d.cm[ix(b)];
  double Eh[3];
  rotate(E, d.ch[ix(b)].data(), Eh);
  double EI[9];  // E I, column-major
  for (int j = 0; j < 3; ++j) rotate(E, I + 3 * j, EI + 3 * j);
  const double rEh = r[0] * Eh[0] + r[1] * Eh[1] + r[2] * Eh[2];
  const double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      double x = EI[i] * E[j] + EI[i + 3] * E[j + 3] + EI[i + 6] * E[j + 6];  // (E I Eᵀ)(i, j)
      x -= Eh[i] * r[j] + r[i] * Eh[j] + m * r[i] * r[j];
      if (i == j) x += 2.0 * rEh + m * rr;
      Ip[i + 3 * j] += x;
    }
  double* hp = d.ch[ix(p)].data();
  for (int i = 0; i < 3; ++i) hp[i] += Eh[i] + m * r[i];
  d.cm[ix(p)] += m;
}

/// World-aligned Jacobian columns of the world point pt carried by body b (added to J).
inline void bodyJacobian(const Data& d, int b, const double* pt, Jacobian& J) noexcept {
  double* Jp = J.data();
  for (int c = b; c > 0; c = parentOf[c]) {
    double w[3], u[3], dp[3], wxd[3];
    rotate(d.R[ix(c)].data(), S6[c], w);
    rotate(d.R[ix(c)].data(), S6[c] + 3, u);
    for (int i = 0; i < 3; ++i) dp[i] = pt[i] - d.p[ix(c)][i];
    cross(w, dp, wxd);
    double* col = Jp + 6 * vIndex[c];
    const double g = gain[c];
    for (int i = 0; i < 3; ++i) {
      col[i] += g * w[i];
      col[3 + i] += g * (u[i] + wxd[i]);
    }
  }
  if (floating_base) {
    const double* R0 = d.R[0].data();
    double dp[3];
    for (int i = 0; i < 3; ++i) dp[i] = pt[i] - d.p[0][i];
    for (int k = 0; k < 3; ++k) {
      double lin[3];
      cross(R0 + 3 * k, dp, lin);  // −[dp]× R0 e_k
      for (int i = 0; i < 3; ++i) {
        Jp[6 * k + i] += R0[3 * k + i];
        Jp[6 * k + 3 + i] += lin[i];
        Jp[6 * (3 + k) + 3 + i] += R0[3 * k + i];
      }
    }
  }
}

/// A frame's placement on its body and a point given in the frame, in body coordinates.
inline void pointOnBody(int frame, const double* point, double* r) noexcept {
  const double* Rf = frame_R[frame];
  for (int i = 0; i < 3; ++i)
    r[i] = frame_p[frame][i] + Rf[3 * i] * point[0] + Rf[3 * i + 1] * point[1] + Rf[3 * i + 2] * point[2];
}

/// x_frame = Rfᵀ x_body.
inline void bodyToFrame(int frame, const double* x, double* out) noexcept {
  const double* Rf = frame_R[frame];
  for (int i = 0; i < 3; ++i) out[i] = Rf[i] * x[0] + Rf[3 + i] * x[1] + Rf[6 + i] * x[2];
}

)";
}

const char* runtimePublicFunctions() {
  return R"(int frameIndex(const char* name) noexcept {
  for (int i = 0; i < nframes; ++i)
    if (std::strcmp(frame_names[ix(i)], name) == 0) return i;
  return -1;
}

void forwardKinematics(Data& d, const ConfigVector& q) noexcept {
  localTransforms(d, q);
  worldPoses(d);
}

void forwardKinematics(Data& d, const ConfigVector& q, const TangentVector& v) noexcept {
  localTransforms(d, q);
  worldPoses(d);
  forwardPass(d, v, nullptr, false, false, d.abias);
}

Pose framePose(const Data& d, int frame) noexcept {
  const int b = frame_body[ix(frame)];
  const double* Rf = frame_R[frame];
  const double* Rb = d.R[ix(b)].data();
  Pose out;
  double* R = out.R.data();
  for (int j = 0; j < 3; ++j) {
    const double col[3] = {Rf[j], Rf[3 + j], Rf[6 + j]};
    rotate(Rb, col, R + 3 * j);
  }
  rotate(Rb, frame_p[frame], out.p.data());
  for (int i = 0; i < 3; ++i) out.p(i) += d.p[ix(b)](i);
  return out;
}

void frameJacobian(const Data& d, int frame, const Eigen::Vector3d& point, ReferenceFrame rf,
                   Jacobian& J) noexcept {
  const int b = frame_body[ix(frame)];
  double r[3], pt[3];
  pointOnBody(frame, point.data(), r);
  rotate(d.R[ix(b)].data(), r, pt);
  for (int i = 0; i < 3; ++i) pt[i] += d.p[ix(b)](i);
  J.setZero();
  bodyJacobian(d, b, pt, J);
  if (rf == ReferenceFrame::Local) {
    double* Jp = J.data();
    for (int c = 0; c < nv; ++c) {
      double x[3];
      for (int h = 0; h < 2; ++h) {
        double* seg = Jp + 6 * c + 3 * h;
        rotateT(d.R[ix(b)].data(), seg, x);  // world -> body
        bodyToFrame(frame, x, seg);      // body -> frame
      }
    }
  }
}

Motion frameBiasAcceleration(const Data& d, int frame, const Eigen::Vector3d& point,
                             ReferenceFrame rf) noexcept {
  const int b = frame_body[ix(frame)];
  double r[3];
  pointOnBody(frame, point.data(), r);
  const double* w = d.v[ix(b)].data();
  const double* vl = w + 3;
  const double* dw = d.abias[ix(b)].data();
  const double* dl = dw + 3;
  double spatial[3], t[3];
  cross(dw, r, t);
  for (int i = 0; i < 3; ++i) spatial[i] = dl[i] + t[i];  // spatial acceleration at the point
  Motion out;
  if (rf == ReferenceFrame::Local) {
    bodyToFrame(frame, dw, out.data());
    bodyToFrame(frame, spatial, out.data() + 3);
  } else {
    double vp[3], wr[3], wvp[3], classical[3];
    cross(w, r, wr);
    for (int i = 0; i < 3; ++i) vp[i] = vl[i] + wr[i];
    cross(w, vp, wvp);
    for (int i = 0; i < 3; ++i) classical[i] = spatial[i] + wvp[i];
    rotate(d.R[ix(b)].data(), dw, out.data());
    rotate(d.R[ix(b)].data(), classical, out.data() + 3);
  }
  return out;
}

void rnea(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,
          TangentVector& tau) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, &a, true, true, d.a);
  backwardTorques(d, tau);
}

void nonLinearEffects(Data& d, const ConfigVector& q, const TangentVector& v, TangentVector& N) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, nullptr, true, true, d.a);
  backwardTorques(d, N);
}

Eigen::Vector3d centerOfMass(const Data& d) noexcept {
  double s[3] = {0.0, 0.0, 0.0};
  for (int b = 0; b < nbodies; ++b) {
    double Rh[3];
    rotate(d.R[ix(b)].data(), bodyFirstMoment[b], Rh);
    for (int i = 0; i < 3; ++i) s[i] += bodyMass[b] * d.p[ix(b)](i) + Rh[i];
  }
  const double inv = totalMass() > 0.0 ? 1.0 / totalMass() : 0.0;
  return Eigen::Vector3d(s[0] * inv, s[1] * inv, s[2] * inv);
}

void comJacobian(Data& d, ComJacobian& Jc) noexcept {
  // d.ch[b] <- Σ m_i c_i (world) over the subtree of b; joint b's column is
  // g_b (w × (s_b − m_sub p_b) + m_sub u) / M with (w; u) = R_b S_b.
  const double inv = totalMass() > 0.0 ? 1.0 / totalMass() : 0.0;
  for (int b = 0; b < nbodies; ++b) {
    double Rh[3];
    rotate(d.R[ix(b)].data(), bodyFirstMoment[b], Rh);
    for (int i = 0; i < 3; ++i) d.ch[ix(b)](i) = bodyMass[b] * d.p[ix(b)](i) + Rh[i];
  }
  for (int b = nbodies - 1; b > 0; --b) d.ch[ix(parentOf[b])] += d.ch[ix(b)];
  Jc.setZero();
  double* Jp = Jc.data();
  for (int b = 1; b < nbodies; ++b) {
    double w[3], u[3], rel[3], wr[3];
    rotate(d.R[ix(b)].data(), S6[b], w);
    rotate(d.R[ix(b)].data(), S6[b] + 3, u);
    for (int i = 0; i < 3; ++i) rel[i] = d.ch[ix(b)](i) - subtreeMass[b] * d.p[ix(b)](i);
    cross(w, rel, wr);
    double* col = Jp + 3 * vIndex[b];
    for (int i = 0; i < 3; ++i) col[i] += gain[b] * inv * (wr[i] + subtreeMass[b] * u[i]);
  }
  if (floating_base) {
    const double* R0 = d.R[0].data();
    double rel[3];
    for (int i = 0; i < 3; ++i) rel[i] = d.ch[0](i) * inv - d.p[0](i);
    for (int k = 0; k < 3; ++k) {
      double lin[3];
      cross(R0 + 3 * k, rel, lin);
      for (int i = 0; i < 3; ++i) {
        Jp[3 * k + i] = lin[i];
        Jp[3 * (3 + k) + i] = R0[3 * k + i];
      }
    }
  }
}

void regressor(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,
               Regressor& Y) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, &a, true, false, d.a);
  Y.setZero();
  double* Yp = Y.data();
  double A[6][10];
  for (int b = floating_base ? 0 : 1; b < nbodies; ++b) {
    bodyRegressor(d.v[ix(b)].data(), d.a[ix(b)].data(), A);
    for (int c = b;;) {
      if (c == 0) {
        for (int i = 0; i < 6; ++i)
          for (int k = 0; k < 10; ++k) Yp[i + nv * (10 * b + k)] += A[i][k];
        break;
      }
      for (int k = 0; k < 10; ++k) {
        double x = 0.0;
        for (int i = 0; i < 6; ++i) x += S6[c][i] * A[i][k];
        Yp[vIndex[c] + nv * (10 * b + k)] += gain[c] * x;
      }
      const int p = parentOf[c];
      if (p == 0 && !floating_base) break;
      for (int k = 0; k < 10; ++k) {
        const double f[6] = {A[0][k], A[1][k], A[2][k], A[3][k], A[4][k], A[5][k]};
        double g[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        forceToParent(d.Rl[ix(c)].data(), d.pl[ix(c)].data(), f, g);
        for (int i = 0; i < 6; ++i) A[i][k] = g[i];
      }
      c = p;
    }
  }
}

void inertialParameters(ParamVector& phi) noexcept {
  double* x = phi.data();
  for (int b = 0; b < nbodies; ++b) {
    const double* I = bodyRotationalInertia[b];  // column-major, symmetric
    const double vals[10] = {bodyMass[b], bodyFirstMoment[b][0], bodyFirstMoment[b][1], bodyFirstMoment[b][2],
                             I[0], I[3], I[4], I[6], I[7], I[8]};
    for (int k = 0; k < 10; ++k) x[10 * b + k] = vals[k];
  }
}

void neutral(ConfigVector& q) noexcept {
  q.setZero();
  if (floating_base) q(3) = 1.0;
}

)";
}

}  // namespace mrqp::gen
