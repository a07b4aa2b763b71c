// Algorithms of every generated model that walk its tables (S6, vIndex, gain, parentOf,
// subtreeMass, bodyMass, bodyFirstMoment, bodyRotationalInertia, comDiagonal, bodyCom,
// bodyComInertia, frame_R, frame_p) and its Data: mrqp-gen copies the text after the marker line
// into the anonymous namespace of each generated .cpp, after the model's tables and kernels.hpp.
// The frame Jacobians' walk is unrolled at compile time instead: one function per body
// (chainColumns), whose joint facts are constants of the template.
// Compiled in every generated model and tested there against the reference implementation
// (tests/model_gen/test_generated_models.cpp).
#pragma once

// ---- mrqp-gen: the text below is copied into every generated model ----
/// A joint's motion subspace S6[b] classified once, at compile time: revolute (part 0: the axis is
/// the angular half), prismatic (part 3) or none (−1, the root); when the axis is ±e_k of the body
/// frame (most robots), its world direction is ±column k of R_b and needs no arithmetic. `scale`
/// is the sign times the joint's gain (mimic multiplier), so that a column needs no further factor.
struct JointAxis {
  int part;
  int column;  ///< k when the axis is ±e_k, else −1
  double scale;
};

constexpr std::array<JointAxis, nbodies> makeJointAxes() noexcept {
  std::array<JointAxis, nbodies> out{};
  for (int b = 0; b < nbodies; ++b) {
    JointAxis a{-1, -1, 1.0};
    for (int part = 0; part <= 3; part += 3)
      if (S6[b][part] != 0.0 || S6[b][part + 1] != 0.0 || S6[b][part + 2] != 0.0) a.part = part;
    if (a.part >= 0) {
      int nonzero = 0;
      for (int k = 0; k < 3; ++k)
        if (S6[b][a.part + k] != 0.0) {
          ++nonzero;
          a.column = k;
          a.scale = S6[b][a.part + k];
        }
      if (nonzero != 1 || (a.scale != 1.0 && a.scale != -1.0)) {
        a.column = -1;
        a.scale = 1.0;
      }
    }
    a.scale *= gain[b];
    out[ix(b)] = a;
  }
  return out;
}
constexpr std::array<JointAxis, nbodies> jointAxes = makeJointAxes();

/// True when every joint axis is ±e_k of its body frame: the general rotation below is then not
/// compiled at all (a branch the compiler would otherwise evaluate on both sides).
constexpr bool makeAllUnitAxes() noexcept {
  for (int b = 1; b < nbodies; ++b)
    if (jointAxes[ix(b)].column < 0) return false;
  return true;
}
constexpr bool allUnitAxes = makeAllUnitAxes();

/// World direction of body b's joint axis times the joint's gain, g_b R_b a.
inline void scaledJointAxisWorld(const Data& d, int b, double* out) noexcept {
  const JointAxis& j = jointAxes[ix(b)];
  const double* R = d.R[ix(b)].data();
  if (allUnitAxes || j.column >= 0) {
    const double* col = R + 3 * j.column;
    for (int i = 0; i < 3; ++i) out[i] = j.scale * col[i];
  } else {
    rotate(R, S6[b] + (j.part > 0 ? j.part : 0), out);
    for (int i = 0; i < 3; ++i) out[i] *= j.scale;
  }
}

/// True for a body whose joint coordinate no other body shares (only mimic joints share one).
constexpr std::array<bool, nbodies> makeCoordinateUnique() noexcept {
  std::array<bool, nbodies> out{};
  for (int b = 1; b < nbodies; ++b) {
    out[ix(b)] = true;
    for (int c = 1; c < nbodies; ++c)
      if (c != b && vIndex[c] == vIndex[b]) out[ix(b)] = false;
  }
  return out;
}
constexpr std::array<bool, nbodies> coordinateUnique = makeCoordinateUnique();

/// nv · vIndex[b]: where the column of body b's coordinate starts in a column-major nv × nv matrix.
constexpr std::array<int, nbodies> makeColumnStart() noexcept {
  std::array<int, nbodies> out{};
  for (int b = 1; b < nbodies; ++b) out[ix(b)] = nv * vIndex[b];
  return out;
}
constexpr std::array<int, nbodies> columnStart = makeColumnStart();

/// True for a body whose chain (the body and its ancestors with a joint) holds no coordinate twice:
/// its Jacobian columns are then each written by one joint.
constexpr std::array<bool, nbodies> makeChainUnique() noexcept {
  std::array<bool, nbodies> out{};
  for (int b = 0; b < nbodies; ++b) {
    out[ix(b)] = true;
    for (int c = b; c > 0; c = parentOf[c])
      for (int e = parentOf[c]; e > 0; e = parentOf[e])
        if (vIndex[c] == vIndex[e]) out[ix(b)] = false;
  }
  return out;
}
constexpr std::array<bool, nbodies> chainUnique = makeChainUnique();

/// A run of consecutive entries of a column-major matrix that an algorithm does not assign and
/// therefore sets to zero first: the structural zeros and the entries it accumulates (mimics).
struct ZeroRun {
  int start;
  int count;
};

/// Number of runs of false in flags[0, n) and, when out is given, the runs themselves.
template <std::size_t N>
constexpr int collectZeroRuns(const bool (&flags)[N], int n, ZeroRun* out) noexcept {
  int runs = 0;
  for (int k = 0; k < n;) {
    if (flags[k]) {
      ++k;
      continue;
    }
    int e = k;
    while (e < n && !flags[e]) ++e;
    if (out != nullptr) out[runs] = ZeroRun{k, e - k};
    ++runs;
    k = e;
  }
  return runs;
}

/// Sets the entries of the runs [begin, end) of x to zero.
inline void zeroRuns(double* x, const ZeroRun* begin, const ZeroRun* end) noexcept {
  for (const ZeroRun* z = begin; z != end; ++z)
    for (int k = 0; k < z->count; ++k) x[z->start + k] = 0.0;
}

/// Entries of the Jacobian (6 × nv, column-major) of a point on body b that bodyJacobian assigns:
/// the free-flyer columns and, when b's chain holds no coordinate twice, the chain's columns.
constexpr void markJacobianAssigned(int b, bool (&assigned)[6 * nv + 1]) noexcept {
  for (int k = 0; k < 6 * nv; ++k) assigned[k] = floating_base && k < 36;
  if (!chainUnique[ix(b)]) return;
  for (int c = b; c > 0; c = parentOf[c])
    for (int i = 0; i < 6; ++i) assigned[6 * vIndex[c] + i] = true;
}

constexpr int countJacobianZeroRuns() noexcept {
  int n = 0;
  for (int b = 0; b < nbodies; ++b) {
    bool assigned[6 * nv + 1] = {};
    markJacobianAssigned(b, assigned);
    n += collectZeroRuns(assigned, 6 * nv, nullptr);
  }
  return n;
}
constexpr int nJacobianZeroRuns = countJacobianZeroRuns();

/// The zero runs of every body's Jacobian: body b's are runs[first[b]] .. runs[first[b + 1] − 1].
struct JacobianZeroRuns {
  std::array<ZeroRun, ix(nJacobianZeroRuns)> runs;
  std::array<int, ix(nbodies + 1)> first;
};

constexpr JacobianZeroRuns makeJacobianZeroRuns() noexcept {
  JacobianZeroRuns out{};
  int n = 0;
  for (int b = 0; b < nbodies; ++b) {
    bool assigned[6 * nv + 1] = {};
    markJacobianAssigned(b, assigned);
    out.first[ix(b)] = n;
    ZeroRun buffer[3 * nv + 1] = {};
    const int k = collectZeroRuns(assigned, 6 * nv, buffer);
    for (int i = 0; i < k; ++i) out.runs[ix(n + i)] = buffer[i];
    n += k;
  }
  out.first[ix(nbodies)] = n;
  return out;
}
constexpr JacobianZeroRuns jacobianZeroRuns = makeJacobianZeroRuns();

/// *out = x (Assign) or *out += x.
template <bool Assign>
inline void put(double* out, double x) noexcept {
  if (Assign)
    *out = x;
  else
    *out += x;
}

/// g_c (the mimic gain) times the world direction of joint c's axis, with all that is known of the
/// axis resolved at compile time: an axis ±e_k of the body frame reads column k of R_c, negated or
/// scaled only when g_c·(±1) is not 1.
template <int C>
inline void jointAxisWorld(const Data& d, double* a) noexcept {
  constexpr JointAxis j = jointAxes[ix(C)];
  const double* R = d.R[ix(C)].data();
  if constexpr (j.column >= 0) {
    const double* col = R + 3 * j.column;
    if constexpr (j.scale == 1.0) {
      a[0] = col[0];
      a[1] = col[1];
      a[2] = col[2];
    } else if constexpr (j.scale == -1.0) {
      a[0] = -col[0];
      a[1] = -col[1];
      a[2] = -col[2];
    } else {
      a[0] = j.scale * col[0];
      a[1] = j.scale * col[1];
      a[2] = j.scale * col[2];
    }
  } else {
    rotate(R, S6[C] + (j.part > 0 ? j.part : 0), a);
    for (int i = 0; i < 3; ++i) a[i] *= j.scale;
  }
}

/// The columns of joint C and of every joint above it in the world-aligned Jacobian of the world
/// point pt: a revolute joint c gives g_c (a, a × (pt − p_c)), a prismatic one g_c (0, a), a = R_c's
/// joint axis; assigned (Assign) or added. One function per body, each with its joint's column
/// offset, axis and gain as constants, ending in a tail call of its parent's: the code stays
/// linear in the number of bodies (not inlined into one another) and a column costs no table look-up.
template <int C, bool Assign>
[[gnu::noinline]] void chainColumns(const Data& d, const double* pt, double* Jp) noexcept {
  if constexpr (C > 0) {
    double a[3];
    jointAxisWorld<C>(d, a);
    double* out = Jp + 6 * vIndex[C];
    if constexpr (jointAxes[ix(C)].part == 0) {
      const double* pc = d.p[ix(C)].data();
      const double dp0 = pt[0] - pc[0], dp1 = pt[1] - pc[1], dp2 = pt[2] - pc[2];
      put<Assign>(out, a[0]);
      put<Assign>(out + 1, a[1]);
      put<Assign>(out + 2, a[2]);
      put<Assign>(out + 3, a[1] * dp2 - a[2] * dp1);
      put<Assign>(out + 4, a[2] * dp0 - a[0] * dp2);
      put<Assign>(out + 5, a[0] * dp1 - a[1] * dp0);
    } else {
      put<Assign>(out + 3, a[0]);
      put<Assign>(out + 4, a[1]);
      put<Assign>(out + 5, a[2]);
      if (Assign) out[0] = out[1] = out[2] = 0.0;
    }
    if constexpr (parentOf[C] > 0) chainColumns<parentOf[C], Assign>(d, pt, Jp);
  } else {
    (void)d;
    (void)pt;
    (void)Jp;
  }
}

/// chainColumns of each body b (assigning when b's chain holds no coordinate twice, else adding).
using ChainColumnsFn = void (*)(const Data&, const double*, double*) noexcept;
template <int... B>
constexpr std::array<ChainColumnsFn, nbodies> makeChainColumnsFns(std::integer_sequence<int, B...>) noexcept {
  return {{&chainColumns<B, chainUnique[ix(B)]>...}};
}
constexpr std::array<ChainColumnsFn, nbodies> chainColumnsOf =
    makeChainColumnsFns(std::make_integer_sequence<int, nbodies>{});

/// World-aligned Jacobian of the world point pt carried by body b, written whole, each entry once
/// where no mimic joints share a column: the columns no joint of b's chain moves (and the columns
/// shared by mimic joints, then accumulated) are zeroed (jacobianZeroRuns), the others assigned.
inline void bodyJacobian(const Data& d, int b, const double* pt, Jacobian& J) noexcept {
  double* Jp = J.data();
  zeroRuns(Jp, jacobianZeroRuns.runs.data() + jacobianZeroRuns.first[ix(b)],
           jacobianZeroRuns.runs.data() + jacobianZeroRuns.first[ix(b + 1)]);
  chainColumnsOf[ix(b)](d, pt, Jp);
  if (floating_base) {
    const double* R = d.R[0].data();
    // Copied first: the stores to J cannot then force R0 to be read again.
    const double R0[9] = {R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8]};
    double dp[3];
    for (int i = 0; i < 3; ++i) dp[i] = pt[i] - d.p[0][i];
    for (int k = 0; k < 3; ++k) {
      double lin[3];
      cross(R0 + 3 * k, dp, lin);  // −[dp]× R0 e_k
      for (int i = 0; i < 3; ++i) {
        Jp[6 * k + i] = R0[3 * k + i];
        Jp[6 * k + 3 + i] = lin[i];
        Jp[6 * (3 + k) + i] = 0.0;
        Jp[6 * (3 + k) + 3 + i] = R0[3 * k + i];
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

/// Entries of the mass matrix (nv × nv, column-major) that crba assigns: the free-flyer block and,
/// for joints whose coordinate no other joint shares, their diagonal entry, their free-flyer row
/// and column, and their entries with each ancestor joint of the same kind. Every other entry is
/// either a structural zero (two joints on different branches) or accumulated (mimic joints).
constexpr void markMassAssigned(bool (&assigned)[nv * nv + 1]) noexcept {
  for (int k = 0; k < nv * nv; ++k) assigned[k] = false;
  if (floating_base)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) assigned[i + nv * j] = true;
  for (int b = 1; b < nbodies; ++b) {
    if (!coordinateUnique[ix(b)]) continue;
    const int vb = vIndex[b];
    assigned[vb + nv * vb] = true;
    if (floating_base)
      for (int k = 0; k < 6; ++k) assigned[k + nv * vb] = assigned[vb + nv * k] = true;
    for (int c = parentOf[b]; c > 0; c = parentOf[c])
      if (coordinateUnique[ix(c)]) assigned[vb + nv * vIndex[c]] = assigned[vIndex[c] + nv * vb] = true;
  }
}

constexpr int countMassZeroRuns() noexcept {
  bool assigned[nv * nv + 1] = {};
  markMassAssigned(assigned);
  return collectZeroRuns(assigned, nv * nv, nullptr);
}
constexpr int nMassZeroRuns = countMassZeroRuns();

constexpr std::array<ZeroRun, ix(nMassZeroRuns)> makeMassZeroRuns() noexcept {
  bool assigned[nv * nv + 1] = {};
  markMassAssigned(assigned);
  ZeroRun buffer[ix(nMassZeroRuns) + 1] = {};
  collectZeroRuns(assigned, nv * nv, buffer);
  std::array<ZeroRun, ix(nMassZeroRuns)> out{};
  for (int i = 0; i < nMassZeroRuns; ++i) out[ix(i)] = buffer[i];
  return out;
}
constexpr std::array<ZeroRun, ix(nMassZeroRuns)> massZeroRuns = makeMassZeroRuns();

/// Composite-rigid-body algorithm in one frame, O: axes aligned with the world at the root's origin.
/// Each body's inertia is moved to O once: about its centre of mass when the inertia there is
/// diagonal in body axes (comDiagonal: I_O = E D Eᵀ + m (|r_c|² 1 − r_c r_cᵀ), h = m r_c,
/// r_c = r + E c), else from the body origin (I_O = E I Eᵀ + Σ_{k≠i} r_k (Eh_k + h_k) on the
/// diagonal, −(Eh_i r_j + r_i h_j) off it, h = E h_b + m r); a body's composite is then the
/// plain sum of its subtree's, with no transform between a body and its parent; a joint is the
/// Plücker vector s_b = g_b (w, r_b × w + u) at O (r_b = p_b − p_0; (w, u) = R_b S_b; g_b the mimic
/// gain), F_b = I^C_b s_b and M(v_c, v_b) = s_cᵀ F_b for b and each ancestor c with a joint. The
/// free-flyer's columns are F_b in root axes. M is written once: the structural zeros and the
/// entries mimic joints accumulate are zeroed first (massZeroRuns), every other entry is assigned;
/// the caller assigns the free-flyer block from d.cm/ch/cI[0], which hold on return the whole
/// robot's inertia in root axes at the root origin. Needs d.Rl, d.pl (localTransforms); sets d.R, d.p.
inline void crbaAtRoot(Data& d, MassMatrix& M) noexcept {
  worldPoses(d);
  double* Mp = M.data();
  zeroRuns(Mp, massZeroRuns.data(), massZeroRuns.data() + nMassZeroRuns);
  const double* p0 = d.p[0].data();
  double S[nbodies][6];   // g_b s_b at O
  double C[nbodies][10];  // m, h, I (xx, yx, zx, yy, zy, zz) at O: the body's own, then its composite
  for (int b = 0; b < nbodies; ++b) {
    const double* E = d.R[ix(b)].data();
    const double r[3] = {d.p[ix(b)](0) - p0[0], d.p[ix(b)](1) - p0[1], d.p[ix(b)](2) - p0[2]};
    const double m = bodyMass[b];
    double* c = C[b];
    c[0] = m;
    if (comDiagonal[b]) {
      // About the centre of mass rc = r + E com: I_O = E D Eᵀ + m (|rc|² 1 − rc rcᵀ), h = m rc.
      const double* D = bodyComInertia[b];
      double Ec[3];
      rotate(E, bodyCom[b], Ec);
      const double rc[3] = {r[0] + Ec[0], r[1] + Ec[1], r[2] + Ec[2]};
      const double h[3] = {m * rc[0], m * rc[1], m * rc[2]};
      const double t[3] = {rc[0] * h[0], rc[1] * h[1], rc[2] * h[2]};
      const double ED[9] = {E[0] * D[0], E[1] * D[0], E[2] * D[0], E[3] * D[1], E[4] * D[1],
                            E[5] * D[1], E[6] * D[2], E[7] * D[2], E[8] * D[2]};
      auto ede = [&](int i, int j) { return ED[i] * E[j] + ED[i + 3] * E[j + 3] + ED[i + 6] * E[j + 6]; };
      c[1] = h[0];
      c[2] = h[1];
      c[3] = h[2];
      c[4] = ede(0, 0) + (t[1] + t[2]);
      c[5] = ede(1, 0) - h[1] * rc[0];
      c[6] = ede(2, 0) - h[2] * rc[0];
      c[7] = ede(1, 1) + (t[0] + t[2]);
      c[8] = ede(2, 1) - h[2] * rc[1];
      c[9] = ede(2, 2) + (t[0] + t[1]);
    } else {
      const double* I = bodyRotationalInertia[b];
      double Eh[3];
      rotate(E, bodyFirstMoment[b], Eh);
      double EI[9];  // E I, column-major
      for (int j = 0; j < 3; ++j) rotate(E, I + 3 * j, EI + 3 * j);
      const double h[3] = {Eh[0] + m * r[0], Eh[1] + m * r[1], Eh[2] + m * r[2]};
      const double t[3] = {r[0] * (Eh[0] + h[0]), r[1] * (Eh[1] + h[1]), r[2] * (Eh[2] + h[2])};
      auto eie = [&](int i, int j) { return EI[i] * E[j] + EI[i + 3] * E[j + 3] + EI[i + 6] * E[j + 6]; };
      c[1] = h[0];
      c[2] = h[1];
      c[3] = h[2];
      c[4] = eie(0, 0) + t[1] + t[2];
      c[5] = eie(1, 0) - (Eh[1] * r[0] + r[1] * h[0]);
      c[6] = eie(2, 0) - (Eh[2] * r[0] + r[2] * h[0]);
      c[7] = eie(1, 1) + t[0] + t[2];
      c[8] = eie(2, 1) - (Eh[2] * r[1] + r[2] * h[1]);
      c[9] = eie(2, 2) + t[0] + t[1];
    }
    if (b == 0) continue;
    double a[3];
    scaledJointAxisWorld(d, b, a);
    double* s = S[b];
    if (jointAxes[ix(b)].part == 0) {
      s[0] = a[0];
      s[1] = a[1];
      s[2] = a[2];
      cross(r, a, s + 3);
    } else {
      s[0] = s[1] = s[2] = 0.0;
      s[3] = a[0];
      s[4] = a[1];
      s[5] = a[2];
    }
  }
  const double* R0 = d.R[0].data();
  for (int b = nbodies - 1; b > 0; --b) {
    const double* s = S[b];
    const double* c = C[b];
    // F = I^C s: n = I w + h × v, f = m v − h × w.
    const double F[6] = {c[4] * s[0] + c[5] * s[1] + c[6] * s[2] + (c[2] * s[5] - c[3] * s[4]),
                         c[5] * s[0] + c[7] * s[1] + c[8] * s[2] + (c[3] * s[3] - c[1] * s[5]),
                         c[6] * s[0] + c[8] * s[1] + c[9] * s[2] + (c[1] * s[4] - c[2] * s[3]),
                         c[0] * s[3] - (c[2] * s[2] - c[3] * s[1]),
                         c[0] * s[4] - (c[3] * s[0] - c[1] * s[2]),
                         c[0] * s[5] - (c[1] * s[1] - c[2] * s[0])};
    double* cp = C[parentOf[b]];
    for (int k = 0; k < 10; ++k) cp[k] += c[k];
    const int vi = vIndex[b];
    double* col = Mp + columnStart[ix(b)];
    const bool unique = coordinateUnique[ix(b)];
    const double diag = s[0] * F[0] + s[1] * F[1] + s[2] * F[2] + s[3] * F[3] + s[4] * F[4] + s[5] * F[5];
    if (unique)
      col[vi] = diag;
    else
      col[vi] += diag;
    for (int a = parentOf[b]; a > 0; a = parentOf[a]) {
      const double* sa = S[a];
      const double x =
          sa[0] * F[0] + sa[1] * F[1] + sa[2] * F[2] + sa[3] * F[3] + sa[4] * F[4] + sa[5] * F[5];
      const int va = vIndex[a];
      double* row = Mp + vi + columnStart[ix(a)];  // M(vi, va)
      if (unique && coordinateUnique[ix(a)]) {
        col[va] = x;
        *row = x;
      } else {
        col[va] += x;
        *row += x;
      }
    }
    if (floating_base) {
      double Fr[6];
      rotateT(R0, F, Fr);
      rotateT(R0, F + 3, Fr + 3);
      if (unique)
        for (int k = 0; k < 6; ++k) col[k] = Mp[vi + nv * k] = Fr[k];
      else
        for (int k = 0; k < 6; ++k) {
          col[k] += Fr[k];
          Mp[vi + nv * k] += Fr[k];
        }
    }
  }
  // The whole robot at the root origin in root axes: I ← R0ᵀ I R0, h ← R0ᵀ h.
  const double* c0 = C[0];
  const double I0[9] = {c0[4], c0[5], c0[6], c0[5], c0[7], c0[8], c0[6], c0[8], c0[9]};
  double T[9];
  for (int j = 0; j < 3; ++j) rotateT(R0, I0 + 3 * j, T + 3 * j);  // R0ᵀ I
  double* Ir = d.cI[0].data();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      Ir[i + 3 * j] = T[i] * R0[3 * j] + T[i + 3] * R0[3 * j + 1] + T[i + 6] * R0[3 * j + 2];
  rotateT(R0, c0 + 1, d.ch[0].data());
  d.cm[0] = c0[0];
}
