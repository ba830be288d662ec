#include "harness/oracles/mujoco_step.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dropcheck {
namespace {

constexpr double kMinVal = 1e-15;  // mjMINVAL
constexpr int kMaxConPair = 50;    // mjMAXCONPAIR
constexpr double kMinMu = 1e-5;    // mjMINMU

using Mat9 = std::array<double, 9>;  // row-major 3x3, as MuJoCo's mjtNum[9]

// ---- MuJoCo's small vector routines, in its operation order (engine_util_blas.c, _spatial.c) ----

double normalize3(double v[3]) {
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (norm < kMinVal) {
    v[0] = 1, v[1] = 0, v[2] = 0;
  } else {
    const double inv = 1 / norm;
    v[0] *= inv, v[1] *= inv, v[2] *= inv;
  }
  return norm;
}

void normalize4(double v[4]) {
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
  if (norm < kMinVal) {
    v[0] = 1, v[1] = 0, v[2] = 0, v[3] = 0;
  } else {
    const double inv = 1 / norm;
    for (int i = 0; i < 4; ++i) v[i] *= inv;
  }
}

double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void cross(double res[3], const double a[3], const double b[3]) {
  res[0] = a[1] * b[2] - a[2] * b[1];
  res[1] = a[2] * b[0] - a[0] * b[2];
  res[2] = a[0] * b[1] - a[1] * b[0];
}

void rot_vec_mat(double res[3], const double v[3], const double* m) {
  const double t[3] = {m[0] * v[0] + m[1] * v[1] + m[2] * v[2],
                       m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
                       m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
  res[0] = t[0], res[1] = t[1], res[2] = t[2];
}

void rot_vec_mat_t(double res[3], const double v[3], const double* m) {
  const double t[3] = {m[0] * v[0] + m[3] * v[1] + m[6] * v[2],
                       m[1] * v[0] + m[4] * v[1] + m[7] * v[2],
                       m[2] * v[0] + m[5] * v[1] + m[8] * v[2]};
  res[0] = t[0], res[1] = t[1], res[2] = t[2];
}

void add_to_scl3(double* res, const double* v, double s) {
  res[0] += v[0] * s, res[1] += v[1] * s, res[2] += v[2] * s;
}

void scl3(double* res, const double* v, double s) {
  res[0] = v[0] * s, res[1] = v[1] * s, res[2] = v[2] * s;
}

void copy3(double* res, const double* v) {
  res[0] = v[0], res[1] = v[1], res[2] = v[2];
}

// res = mat1' * mat2 (3x3), as mju_mulMatTMat accumulates it.
void mul_mat_t_mat(double* res, const double* a, const double* b) {
  std::fill(res, res + 9, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (const double t = a[i * 3 + j]; t != 0.0)
        for (int k = 0; k < 3; ++k) res[j * 3 + k] += b[i * 3 + k] * t;
}

// res = mat1 * mat2' (3x3), rows dotted as mju_mulMatMatT does.
void mul_mat_mat_t(double* res, const double* a, const double* b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) res[i * 3 + j] = dot3(a + i * 3, b + j * 3);
}

Mat9 quat_to_mat(const double q[4]) {
  if (q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0) return {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double q00 = q[0] * q[0], q01 = q[0] * q[1], q02 = q[0] * q[2], q03 = q[0] * q[3];
  const double q11 = q[1] * q[1], q12 = q[1] * q[2], q13 = q[1] * q[3];
  const double q22 = q[2] * q[2], q23 = q[2] * q[3], q33 = q[3] * q[3];
  return {q00 + q11 - q22 - q33, 2 * (q12 - q03),       2 * (q13 + q02),
          2 * (q12 + q03),       q00 - q11 + q22 - q33, 2 * (q23 - q01),
          2 * (q13 - q02),       2 * (q23 + q01),       q00 - q11 - q22 + q33};
}

void mul_quat(double res[4], const double a[4], const double b[4]) {
  const double t[4] = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                       a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                       a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                       a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  for (int i = 0; i < 4; ++i) res[i] = t[i];
}

// mju_quatIntegrate: q <- normalize(q * (cos(a/2), axis*sin(a/2))), a = h*|w|, w in body axes.
void quat_integrate(double q[4], const double w[3], double h) {
  double axis[3] = {w[0], w[1], w[2]};
  const double angle = h * normalize3(axis);
  double r[4] = {1, 0, 0, 0};
  if (angle != 0) {
    const double s = std::sin(angle * 0.5);
    r[0] = std::cos(angle * 0.5), r[1] = axis[0] * s, r[2] = axis[1] * s, r[3] = axis[2] * s;
  }
  double t[4];
  mul_quat(t, q, r);
  normalize4(t);
  for (int i = 0; i < 4; ++i) q[i] = t[i];
}

// mju_makeFrame: the normal given, a tangent (0, 1, 0) or (0, 0, 1) made orthogonal to it, the
// third their cross product.
void make_frame(double f[9]) {
  normalize3(f);
  f[3] = f[4] = f[5] = 0;
  if (f[1] < 0.5 && f[1] > -0.5)
    f[4] = 1;
  else
    f[5] = 1;
  double t[3];
  scl3(t, f, dot3(f, f + 3));
  f[3] -= t[0], f[4] -= t[1], f[5] -= t[2];
  normalize3(f + 3);
  cross(f + 6, f, f + 3);
}

// ---- Collision: mjc_BoxBox (engine_collision_box.c), its face branch ----

struct Contact {
  double pos[3]{};
  double dist = 0.0;
  double frame[9]{};
};

struct GeomPose {
  const double* pos;
  const double* mat;
  const double* size;
};

// mjc_BoxBox's clipping of segments against a face's rectangle (half sizes half[0], half[1]):
// for segment i (from lines[i][0..2] along lines[i][3..5]) and each rectangle axis q, where it
// crosses x_q = -+half[q] at a parameter t in [0, 1] with its other coordinate inside the
// rectangle, visit(i, q, -+half[q], t, that coordinate).
template <typename Visit>
void clip_segments(const double (*lines)[6], int count, const double* half, Visit visit) {
  for (int i = 0; i < count; ++i)
    for (int q = 0; q < 2; ++q) {
      const double a = lines[i][0 + q], b = lines[i][3 + q];
      const double c = lines[i][1 - q], d = lines[i][4 - q];
      if (!(std::fabs(b) > kMinVal)) continue;
      for (int j = -1; j <= 1; j += 2) {
        const double l = half[q] * j;
        const double t = (l - a) * (1 / b);
        if (t < 0 || t > 1) continue;
        const double other = c + d * t;
        if (std::fabs(other) > half[1 - q]) continue;
        visit(i, q, l, t, other);
      }
    }
}

// Corner i of the face rectangle (-+lx, -+ly) and its coordinates (u, v) in the parallelogram
// pts[0] + u*pts[1] + v*pts[2] (x and y only), det = pts[1] x pts[2]: mjc_BoxBox's test of which
// rectangle corners lie on the other box's face. `det` is passed in because the edge branch, as
// MuJoCo's, overwrites it between corners.
void corner_in_parallelogram(int i, double lx, double ly, const double (*pts)[3], double det,
                             double& cx, double& cy, double& u, double& v) {
  cx = i / 2 ? lx : -lx;
  cy = i % 2 ? ly : -ly;
  const double x = cx - pts[0][0], y = cy - pts[0][1];
  const double a = pts[1][0], b = pts[2][0], c = pts[1][1], d = pts[2][1];
  u = (x * d - y * b) * (1 / det);
  v = (y * a - x * c) * (1 / det);
}

// The axis of the deepest edge pair: which corner of each edge, the normal, and its side.
struct EdgeAxis {
  int cle1 = 0, cle2 = 0;
  double clnorm[3]{};
  bool in = false;
};

// The frame that turns face `face` (0..5: -x, -y... as mjc_BoxBox numbers them) to +z: rotmore,
// and the axis permutation and signs rotaxis applies.
struct FaceTurn {
  double rotmore[9]{};
  int i0 = 0, i1 = 1, i2 = 2;
  double f0 = 1, f1 = 1, f2 = 1;
  void axis(double* res, const double* in) const {
    res[0] = in[i0] * f0, res[1] = in[i1] * f1, res[2] = in[i2] * f2;
  }
  void rows(double* res, const double* in) const {
    scl3(res + 0, in + i0 * 3, f0);
    scl3(res + 3, in + i1 * 3, f1);
    scl3(res + 6, in + i2 * 3, f2);
  }
};

FaceTurn face_turn(int face) {
  FaceTurn t;
  double* r = t.rotmore;
  switch (face) {
    case 0:
      r[2] = -1, r[4] = +1, r[6] = +1;
      t.i0 = 2, t.f0 = -1, t.i2 = 0;
      break;
    case 1:
      r[0] = +1, r[5] = -1, r[7] = +1;
      t.i1 = 2, t.f1 = -1, t.i2 = 1;
      break;
    case 2:
      r[0] = +1, r[4] = +1, r[8] = +1;
      break;
    case 3:
      r[2] = +1, r[4] = +1, r[6] = -1;
      t.i0 = 2, t.i2 = 0, t.f2 = -1;
      break;
    case 4:
      r[0] = +1, r[5] = +1, r[7] = -1;
      t.i1 = 2, t.i2 = 1, t.f2 = -1;
      break;
    default:
      r[0] = -1, r[4] = +1, r[8] = -1;
      t.f0 = -1, t.f2 = -1;
  }
  return t;
}

// mjc_BoxBox's edge-edge branch (its label edgeedge), line by line: the deepest axis is the cross
// product of an edge of each box.
int edge_edge(int code, const EdgeAxis& e, const double* pos1, const double* mat1,
              const double* size1, const double* pos21, const double* size2, const double* rot,
              const double* rotabs, const double* rott, Contact* con) {
  const double margin = 0.0, margin2 = 0.0;
  double rottabs[9], p[3], r[9], rt[9], s[3], tmp1[3], tmp2[3], rnorm[3];
  double points[kMaxConPair][3], depth[kMaxConPair], pts[6][3], ppts2[4][2], pu[4][3], axi[3][3];
  double lines[4][6], linesu[4][6];
  double a, b, c, d, c1, x, y, u, v, llx, lly;
  for (int i = 0; i < 9; ++i) rottabs[i] = std::fabs(rott[i]);
  const int q1 = code / 3, q2 = code % 3;
  int ax1 = 0, ax2 = 0, pax1 = 0, pax2 = 0;
  if (q2 == 0) ax1 = 1, ax2 = 2;
  if (q2 == 1) ax1 = 0, ax2 = 2;
  if (q2 == 2) ax1 = 1, ax2 = 0;
  if (q1 == 0) pax1 = 1, pax2 = 2;
  if (q1 == 1) pax1 = 0, pax2 = 2;
  if (q1 == 2) pax1 = 1, pax2 = 0;
  if (rotabs[3 * q1 + ax1] < rotabs[3 * q1 + ax2]) {
    ax1 = ax2;
    ax2 = 3 - q2 - ax1;
  }
  if (rottabs[3 * q2 + pax1] < rottabs[3 * q2 + pax2]) {
    pax1 = pax2;
    pax2 = 3 - q1 - pax1;
  }
  const int clface = (e.cle1 & (1 << pax2)) ? pax2 : pax2 + 3;
  const FaceTurn t = face_turn(clface);
  t.axis(p, pos21);
  t.axis(rnorm, e.clnorm);
  t.rows(r, rot);
  rot_vec_mat_t(tmp1, size1, t.rotmore);
  for (int i = 0; i < 3; ++i) s[i] = std::fabs(tmp1[i]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[i * 3 + j] = r[j * 3 + i];
  const double lx = s[0], ly = s[1], hz = s[2];
  p[2] -= hz;

  int n = 0;
  copy3(points[n], p);
  add_to_scl3(points[n], rt + 3 * ax1, size2[ax1] * ((e.cle2 & (1 << ax1)) ? 1 : -1));
  add_to_scl3(points[n], rt + 3 * ax2, size2[ax2] * ((e.cle2 & (1 << ax2)) ? 1 : -1));
  copy3(points[n + 1], points[n]);
  add_to_scl3(points[n], rt + 3 * q2, size2[q2]);
  n = 1;
  add_to_scl3(points[n], rt + 3 * q2, -size2[q2]);
  n = 2;
  copy3(points[n], p);
  add_to_scl3(points[n], rt + 3 * ax1, size2[ax1] * ((e.cle2 & (1 << ax1)) ? -1 : 1));
  add_to_scl3(points[n], rt + 3 * ax2, size2[ax2] * ((e.cle2 & (1 << ax2)) ? 1 : -1));
  copy3(points[n + 1], points[n]);
  add_to_scl3(points[n], rt + 3 * q2, size2[q2]);
  n = 3;
  add_to_scl3(points[n], rt + 3 * q2, -size2[q2]);

  copy3(axi[0], points[0]);
  for (int i = 0; i < 3; ++i) {
    axi[1][i] = points[1][i] - points[0][i];
    axi[2][i] = points[2][i] - points[0][i];
  }
  if (std::fabs(rnorm[2]) < kMinVal) return 0;
  const double innorm = (1 / rnorm[2]) * (e.in ? -1 : 1);
  for (int i = 0; i < 4; ++i) {
    c1 = -points[i][2] * (1 / rnorm[2]);
    copy3(pu[i], points[i]);
    add_to_scl3(points[i], rnorm, c1);
    ppts2[i][0] = points[i][0];
    ppts2[i][1] = points[i][1];
  }
  copy3(pts[0], points[0]);
  for (int i = 0; i < 3; ++i) {
    pts[1][i] = points[1][i] - points[0][i];
    pts[2][i] = points[2][i] - points[0][i];
  }
  int k = 0;
  n = 0;
  copy3(lines[k] + 0, pts[0]);
  copy3(lines[k] + 3, pts[1]);
  copy3(linesu[k] + 0, axi[0]);
  copy3(linesu[k++] + 3, axi[1]);
  copy3(lines[k] + 0, pts[0]);
  copy3(lines[k] + 3, pts[2]);
  copy3(linesu[k] + 0, axi[0]);
  copy3(linesu[k++] + 3, axi[2]);
  for (int i = 0; i < 3; ++i) {
    lines[k][i] = pts[0][i] + pts[1][i];
    linesu[k][i] = axi[0][i] + axi[1][i];
  }
  copy3(lines[k] + 3, pts[2]);
  copy3(linesu[k++] + 3, axi[2]);
  for (int i = 0; i < 3; ++i) {
    lines[k][i] = pts[0][i] + pts[2][i];
    linesu[k][i] = axi[0][i] + axi[2][i];
  }
  copy3(lines[k] + 3, pts[1]);
  copy3(linesu[k++] + 3, axi[1]);

  clip_segments(lines, k, s, [&](int i, int q, double l, double t, double other) {
    if (n >= kMaxConPair || (linesu[i][2] + linesu[i][5] * t) * innorm > margin) return;
    scl3(points[n], linesu[i], 0.5);
    add_to_scl3(points[n], linesu[i] + 3, 0.5 * t);
    points[n][0 + q] += 0.5 * l;
    points[n][1 - q] += 0.5 * other;
    depth[n] = points[n][2] * innorm * 2;
    n++;
  });
  const int nl = n;
  a = pts[1][0];
  b = pts[2][0];
  c = pts[1][1];
  d = pts[2][1];
  c1 = a * d - b * c;
  for (int i = 0; i < 4; ++i) {
    if (n >= kMaxConPair) continue;
    corner_in_parallelogram(i, lx, ly, pts, c1, llx, lly, u, v);
    if (nl == 0) {
      if ((u < 0 || u > 1) && (v < 0 || v > 1)) continue;
    } else if (u < 0 || u > 1 || v < 0 || v > 1) {
      continue;
    }
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    scl3(tmp1, pu[0], 1 - u - v);
    add_to_scl3(tmp1, pu[1], u);
    add_to_scl3(tmp1, pu[2], v);
    points[n][0] = llx;
    points[n][1] = lly;
    points[n][2] = 0;
    for (int j = 0; j < 3; ++j) tmp2[j] = points[n][j] - tmp1[j];
    // As in MuJoCo, c1 (the determinant above) now holds the squared distance, and the next
    // corner's u and v divide by it.
    c1 = dot3(tmp2, tmp2);
    if (tmp1[2] > 0 && c1 > margin2) continue;
    for (int j = 0; j < 3; ++j) points[n][j] = (points[n][j] + tmp1[j]) * 0.5;
    depth[n] = std::sqrt(c1) * (tmp1[2] < 0 ? -1 : 1);
    n++;
  }
  const int nf = n;
  for (int i = 0; i < 4; ++i) {
    if (n >= kMaxConPair) continue;
    x = ppts2[i][0];
    y = ppts2[i][1];
    if (nl == 0) {
      if (nf != 0 && (x < -lx || x > lx) && (y < -ly || y > ly)) continue;
    } else if (x < -lx || x > lx || y < -ly || y > ly) {
      continue;
    }
    double dd = 0;
    for (int j = 0; j < 2; ++j)
      if (ppts2[i][j] < -s[j])
        dd += (ppts2[i][j] + s[j]) * (ppts2[i][j] + s[j]);
      else if (ppts2[i][j] > s[j])
        dd += (ppts2[i][j] - s[j]) * (ppts2[i][j] - s[j]);
    dd += pu[i][2] * innorm * pu[i][2] * innorm;
    if (pu[i][2] > 0 && dd > margin2) continue;
    tmp1[0] = ppts2[i][0] * 0.5;
    tmp1[1] = ppts2[i][1] * 0.5;
    tmp1[2] = 0;
    for (int j = 0; j < 2; ++j) {
      if (ppts2[i][j] < -s[j])
        tmp1[j] = -s[j] * 0.5;
      else if (ppts2[i][j] > s[j])
        tmp1[j] = +s[j] * 0.5;
    }
    add_to_scl3(tmp1, pu[i], 0.5);
    copy3(points[n], tmp1);
    depth[n] = std::sqrt(dd) * (pu[i][2] < 0 ? -1 : 1);
    n++;
  }
  mul_mat_mat_t(r, mat1, t.rotmore);
  rot_vec_mat(tmp1, rnorm, r);
  scl3(tmp2, tmp1, e.in ? -1 : 1);
  for (int i = 0; i < n; ++i) {
    con[i].dist = depth[i];
    points[i][2] += hz;
    rot_vec_mat(tmp1, points[i], r);
    for (int j = 0; j < 3; ++j) con[i].pos[j] = tmp1[j] + pos1[j];
    copy3(con[i].frame, tmp2);
  }
  return n;
}

// A face axis and an edge axis this close (relative) are undecided: which one mjc_BoxBox takes
// depends on the last bits of the state. A box resting flat on another has such a tie at every
// step (measured: the two differ by 1e-15 of the depth), and the branches differ by a factor 2 in
// the depth they report (the face branch halves it, the edge branch does not).
constexpr double kUndecidedAxis = 1e-6;

enum class Branch { as_mujoco, other };

// The contacts of boxes g1 and g2 (margin 0), with the normal from g1 to g2: mjc_BoxBox line by
// line, or with `branch` other the face or edge branch it did not take when the two are undecided
// (*undecided says so).
int box_box(const GeomPose& g1, const GeomPose& g2, Contact* con, Branch branch, bool* undecided) {
  const double margin = 0.0;
  const double *pos1 = g1.pos, *mat1 = g1.mat, *size1 = g1.size;
  const double *pos2 = g2.pos, *mat2 = g2.mat, *size2 = g2.size;
  double pos12[3], pos21[3], rot[9], rott[9], rotabs[9], tmp1[3], tmp2[3], plen1[3], plen2[3];
  double p[3], r[9], s[3], ss[3], lp[3], rt[9], points[kMaxConPair][3];
  double pts[6][3], lines[4][6];
  double penetration, c1, c2, c3, a, b, c, d, lx, ly, hz, u, v, llx, lly;
  int code = -1, n = 0;
  EdgeAxis edge;

  for (int i = 0; i < 3; ++i) tmp1[i] = pos2[i] - pos1[i];
  rot_vec_mat_t(pos21, tmp1, mat1);
  for (int i = 0; i < 3; ++i) tmp1[i] = pos1[i] - pos2[i];
  rot_vec_mat_t(pos12, tmp1, mat2);
  mul_mat_t_mat(rot, mat1, mat2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rott[i * 3 + j] = rot[j * 3 + i];
  for (int i = 0; i < 9; ++i) rotabs[i] = std::fabs(rot[i]);
  rot_vec_mat(plen2, size2, rotabs);
  rot_vec_mat_t(plen1, size1, rotabs);

  penetration = margin;
  for (int i = 0; i < 3; ++i) penetration += size1[i] * 3 + size2[i] * 3;
  for (int i = 0; i < 3; ++i) {
    c1 = -std::fabs(pos21[i]) + size1[i] + plen2[i];
    c2 = -std::fabs(pos12[i]) + size2[i] + plen1[i];
    if (c1 < -margin || c2 < -margin) return 0;
    if (c1 < penetration) {
      penetration = c1;
      code = i + 3 * (pos21[i] < 0) + 0;
    }
    if (c2 < penetration) {
      penetration = c2;
      code = i + 3 * (pos12[i] < 0) + 6;
    }
  }
  // The edge-edge axes: a separating one ends the test; a deeper-than-face one takes the edge
  // branch. `near` keeps the deepest edge axis, for the other branch of an undecided pair.
  const double face_penetration = penetration;
  const int face_code = code;
  EdgeAxis near;
  int near_code = -1;
  double near_c3 = INFINITY;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      tmp2[0] = tmp2[1] = tmp2[2] = 0;
      if (i == 0) {
        tmp2[1] = -rott[3 * j + 2];
        tmp2[2] = +rott[3 * j + 1];
      } else if (i == 1) {
        tmp2[0] = +rott[3 * j + 2];
        tmp2[2] = -rott[3 * j + 0];
      } else {
        tmp2[0] = -rott[3 * j + 1];
        tmp2[1] = +rott[3 * j + 0];
      }
      c1 = normalize3(tmp2);
      if (c1 < kMinVal) continue;
      c2 = dot3(pos21, tmp2);
      c3 = 0;
      for (int k = 0; k < 3; ++k)
        if (k != i) c3 += size1[k] * std::fabs(tmp2[k]);
      for (int k = 0; k < 3; ++k)
        if (k != j) c3 += size2[k] * rotabs[3 * i + 3 - k - j] / c1;
      c3 -= std::fabs(c2);
      if (c3 < -margin) return 0;
      const auto axis = [&] {
        EdgeAxis e;
        for (int k = 0; k < 3; ++k)
          if (k != i && ((tmp2[k] > 0) ^ (c2 < 0))) e.cle1 += 1 << k;
        for (int k = 0; k < 3; ++k)
          if (k != j && ((rot[3 * i + 3 - k - j] > 0) ^ (c2 < 0) ^ ((k - j + 3) % 3 == 1)))
            e.cle2 += 1 << k;
        copy3(e.clnorm, tmp2);
        e.in = c2 < 0;
        return e;
      };
      if (c3 < penetration * (1 - 1e-12)) {
        penetration = c3;
        code = 12 + i * 3 + j;
        edge = axis();
      }
      if (c3 < near_c3) {
        near_c3 = c3;
        near_code = 12 + i * 3 + j;
        near = axis();
      }
    }
  }
  if (code == -1) return 0;
  *undecided = near_code >= 0 && face_code >= 0 &&
               std::fabs(near_c3 - face_penetration) <= kUndecidedAxis * face_penetration;
  if (*undecided && branch == Branch::other) {
    if (code >= 12) {
      code = face_code;
    } else {
      code = near_code;
      edge = near;
    }
  }
  if (code >= 12)
    return edge_edge(code - 12, edge, pos1, mat1, size1, pos21, size2, rot, rotabs, rott, con);

  const int q1 = code % 6, q2 = code / 6;
  const FaceTurn turn = face_turn(q1);
  if (q2) {
    mul_mat_mat_t(r, turn.rotmore, rot);
    turn.axis(p, pos12);
    turn.axis(tmp1, size2);
    copy3(s, size1);
  } else {
    turn.rows(r, rot);
    turn.axis(p, pos21);
    turn.axis(tmp1, size1);
    copy3(s, size2);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[i * 3 + j] = r[j * 3 + i];
  for (int i = 0; i < 3; ++i) ss[i] = std::fabs(tmp1[i]);
  lx = ss[0], ly = ss[1], hz = ss[2];
  p[2] -= hz;
  copy3(lp, p);

  int clcorner = 0;
  for (int i = 0; i < 3; ++i)
    if (r[6 + i] < 0) clcorner += 1 << i;
  add_to_scl3(lp, rt + 0, s[0] * ((clcorner & 1) ? 1 : -1));
  add_to_scl3(lp, rt + 3, s[1] * ((clcorner & 2) ? 1 : -1));
  add_to_scl3(lp, rt + 6, s[2] * ((clcorner & 4) ? 1 : -1));

  int m = 0, k = 0;
  copy3(pts[m++], lp);
  for (int i = 0; i < 3; ++i)
    if (std::fabs(r[6 + i]) < 0.5)
      scl3(pts[m++], rt + 3 * i, s[i] * ((clcorner & (1 << i)) ? -2 : 2));
  for (int i = 0; i < 3; ++i) {
    pts[3][i] = pts[0][i] + pts[1][i];
    pts[4][i] = pts[0][i] + pts[2][i];
    pts[5][i] = pts[3][i] + pts[2][i];
  }
  const auto line = [&](const double* from, const double* dir) {
    copy3(lines[k] + 0, from);
    copy3(lines[k++] + 3, dir);
  };
  if (m > 1) line(pts[0], pts[1]);
  if (m > 2) {
    line(pts[0], pts[2]);
    line(pts[3], pts[2]);
    line(pts[4], pts[1]);
  }
  clip_segments(lines, k, ss, [&](int i, int, double, double t, double) {
    copy3(points[n], lines[i]);
    add_to_scl3(points[n++], lines[i] + 3, t);
  });
  a = pts[1][0];
  b = pts[2][0];
  c = pts[1][1];
  d = pts[2][1];
  c1 = a * d - b * c;
  if (m > 2) {
    for (int i = 0; i < 4; ++i) {
      corner_in_parallelogram(i, lx, ly, pts, c1, llx, lly, u, v);
      if (u <= 0 || v <= 0 || u >= 1 || v >= 1) continue;
      points[n][0] = llx;
      points[n][1] = lly;
      points[n][2] = pts[0][2] + u * pts[1][2] + v * pts[2][2];
      n++;
    }
  }
  for (int i = 0; i < (1 << (m - 1)); ++i) {
    copy3(tmp1, pts[i == 0 ? 0 : i + 2]);
    if (i && (tmp1[0] <= -lx || tmp1[0] >= lx)) continue;
    if (i && (tmp1[1] <= -ly || tmp1[1] >= ly)) continue;
    copy3(points[n++], tmp1);
  }
  m = n;
  n = 0;
  for (int i = 0; i < m; ++i) {
    if (points[i][2] > margin) continue;
    copy3(points[n], points[i]);
    points[n][2] *= 0.5;  // the contact sits halfway: dist is half the depth
    n++;
  }
  mul_mat_mat_t(r, q2 ? mat2 : mat1, turn.rotmore);
  copy3(p, q2 ? pos2 : pos1);
  const double sign = q2 ? -1 : 1;
  tmp2[0] = sign * r[2], tmp2[1] = sign * r[5], tmp2[2] = sign * r[8];
  for (int i = 0; i < n; ++i) {
    con[i].dist = points[i][2];
    points[i][2] += hz;
    rot_vec_mat(tmp1, points[i], r);
    for (int j = 0; j < 3; ++j) con[i].pos[j] = tmp1[j] + p[j];
    copy3(con[i].frame, tmp2);
  }
  return n;
}

// ---- Collision: _SphereBox (engine_collision_box.c, mjc_SphereBox), line by line ----

// The contact of sphere g1 (size[0] its radius) and box g2 (margin 0), the normal from the sphere
// to the box: the box point nearest the sphere's centre, or the nearest face when the centre is
// inside the box; its depth from that point; the position halfway between the two surfaces.
int sphere_box(const GeomPose& g1, const GeomPose& g2, Contact* con) {
  const double margin = 0.0;
  const double *size1 = g1.size, *size2 = g2.size, *mat2 = g2.mat;
  double tmp[3], center[3], clamped[3], deepest[3], nearest[3], pos[3];
  for (int k = 0; k < 3; ++k) tmp[k] = g1.pos[k] - g2.pos[k];
  rot_vec_mat_t(center, tmp, mat2);
  copy3(clamped, center);
  for (int k = 0; k < 3; ++k)  // mju_clampVec: a positive limit only
    if (size2[k] > 0) clamped[k] = std::clamp(clamped[k], -size2[k], size2[k]);
  copy3(deepest, center);
  for (int k = 0; k < 3; ++k) tmp[k] = clamped[k] - center[k];
  const double dist = normalize3(tmp);
  if (dist - size1[0] > margin) return 0;
  if (dist <= kMinVal) {
    // The centre inside the box: out through the nearest face.
    double closest = (size2[0] + size2[1] + size2[2]) * 2;
    int face = 0;
    for (int i = 0; i < 6; ++i) {
      const double d = std::fabs((i % 2 ? 1 : -1) * size2[i / 2] - center[i / 2]);
      if (closest > d) closest = d, face = i;
    }
    nearest[0] = nearest[1] = nearest[2] = 0;
    nearest[face / 2] = face % 2 ? -1 : 1;
    copy3(pos, center);
    add_to_scl3(pos, nearest, (size1[0] - closest) / 2);
    rot_vec_mat(con[0].frame, nearest, mat2);
  } else {
    add_to_scl3(deepest, tmp, size1[0]);
    pos[0] = pos[1] = pos[2] = 0;
    add_to_scl3(pos, clamped, 0.5);
    add_to_scl3(pos, deepest, 0.5);
    rot_vec_mat(con[0].frame, tmp, mat2);
  }
  rot_vec_mat(tmp, pos, mat2);
  for (int k = 0; k < 3; ++k) con[0].pos[k] = tmp[k] + g2.pos[k];
  con[0].dist = dist - size1[0];
  con[0].frame[3] = con[0].frame[4] = con[0].frame[5] = 0;
  return 1;
}

// ---- The step ----

struct Geom {
  int body;       // dynamic body index (into the dof blocks), -1 for a static box
  bool sphere;    // a sphere (size[0] its radius), else a box
  double pos[3];  // geom_xpos
  Mat9 mat;       // geom_xmat
  double size[3];
  double friction;
};

struct Pose {
  double pos[3];
  double quat[4];  // qpos, not normalised
  double vel[3];
  double w[3];  // body axes
};

// A contact between geoms, as mj_collideGeoms leaves it.
struct PairContact {
  Contact c;
  const Geom* geom1;  // the normal points from geom1 to geom2
  const Geom* geom2;
  double mu;
};

// Geoms in MuJoCo's order: the worldbody's (static bodies) first, then each dynamic body's, each in
// the scene's order.
std::vector<Geom> geoms_of(const MujocoWorld& w, const std::vector<Pose>& poses,
                           const std::vector<int>& dof_block) {
  std::vector<Geom> out;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
      const MujocoBody& b = w.bodies[i];
      if (b.is_static != (pass == 0)) continue;
      Geom g{};
      g.body = b.is_static ? -1 : dof_block[i];
      g.friction = b.friction;
      g.sphere = b.radius > 0.0;
      for (int k = 0; k < 3; ++k) g.size[k] = g.sphere ? b.radius : b.half_extents[k];
      if (b.is_static) {
        // A worldbody geom: its pos as given, no rotation (the adapter writes none).
        for (int k = 0; k < 3; ++k) g.pos[k] = b.position[k];
        g.mat = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      } else {
        // mj_kinematics: the free joint's position, its quaternion normalised.
        const Pose& p = poses[i];
        double q[4] = {p.quat[0], p.quat[1], p.quat[2], p.quat[3]};
        normalize4(q);
        for (int k = 0; k < 3; ++k) g.pos[k] = p.pos[k];
        g.mat = quat_to_mat(q);
      }
      out.push_back(g);
    }
  return out;
}

// mj_collision: every pair of geoms on different bodies (static geoms share the worldbody), the
// lower geom first, or the sphere first in a sphere-box pair (mj_collideGeoms orders a pair by geom
// type); box-box contacts with repeated positions removed, and those not inside the
// other geom (dist >= 0) excluded as mj_collideGeoms excludes them. A pair numbered in `flip`
// takes the branch mjc_BoxBox did not, if it is undecided; `undecided` gets the numbers of the
// undecided pairs (pairs numbered in the order they are tested).
std::vector<PairContact> collide(const std::vector<Geom>& geoms, const std::vector<int>& flip,
                                 std::vector<int>* undecided) {
  std::vector<PairContact> out;
  int pair = 0;
  for (std::size_t a = 0; a < geoms.size(); ++a)
    for (std::size_t b = a + 1; b < geoms.size(); ++b) {
      const bool swap = geoms[b].sphere && !geoms[a].sphere;
      const Geom &g1 = geoms[swap ? b : a], &g2 = geoms[swap ? a : b];
      if (g1.body < 0 && g2.body < 0) continue;
      if (g1.sphere && g2.sphere)
        throw std::invalid_argument("MuJoCo's re-solve collides no sphere with a sphere");
      const bool flipped = std::find(flip.begin(), flip.end(), pair) != flip.end();
      Contact con[kMaxConPair];
      bool tie = false;
      const GeomPose p1{g1.pos, g1.mat.data(), g1.size}, p2{g2.pos, g2.mat.data(), g2.size};
      const int num = g1.sphere
                          ? sphere_box(p1, p2, con)
                          : box_box(p1, p2, con, flipped ? Branch::other : Branch::as_mujoco, &tie);
      if (tie) undecided->push_back(pair);
      ++pair;
      for (int i = 0; i < num; ++i) {
        bool repeated = false;
        for (int j = i + 1; j < num && !repeated; ++j)
          repeated = con[i].pos[0] == con[j].pos[0] && con[i].pos[1] == con[j].pos[1] &&
                     con[i].pos[2] == con[j].pos[2];
        // Excluded "in the gap": only a contact closer than includemargin (0) makes rows.
        if (repeated || !(con[i].dist < 0)) continue;
        // The larger of the two geoms' frictions, at least mjMINMU.
        PairContact pc{con[i], &g1, &g2, std::max(kMinMu, std::max(g1.friction, g2.friction))};
        make_frame(pc.c.frame);
        out.push_back(pc);
      }
    }
  return out;
}

// Adds sign times the point Jacobian of geom g's body at `point`: d(velocity of the point)/d(qvel)
// for its free joint's 6 dofs, (I | (R e_k) x (point - x)).
void add_point_jacobian(Eigen::MatrixXd& J, const double point[3], const Geom& g, double sign) {
  const int blk = g.body;
  double offset[3];
  for (int k = 0; k < 3; ++k) offset[k] = point[k] - g.pos[k];
  for (int k = 0; k < 3; ++k) {
    J(k, 6 * blk + k) += sign;
    const double axis[3] = {g.mat[0 + k], g.mat[3 + k], g.mat[6 + k]};
    double col[3];
    cross(col, axis, offset);
    for (int r = 0; r < 3; ++r) J(r, 6 * blk + 3 + k) += sign * col[r];
  }
}

struct Rows {
  Eigen::MatrixXd J;     // rows x nv
  Eigen::VectorXd D;     // 1/R
  Eigen::VectorXd aref;  // reference acceleration
  // The elliptic cone: three rows per contact (normal, two tangents), each contact's regularised
  // mu (contact.mu = mu*sqrt(R_1/R_0)) and its friction.
  bool elliptic = false;
  std::vector<double> mu_reg, friction;
};

// mj_instantiateContact, mj_diagApprox, mj_makeImpedance and mj_referenceConstraint. The
// pyramidal cone: per contact four edges J_n +- mu*J_t, all with R = 2*mu_r^2*R_0. The elliptic
// cone: per contact the rows J_n, J_t1, J_t2 with R_0 = (1 - imp)/imp*A on the normal and
// R_0/impratio on the tangents, whose reference has no stiffness (aref = -B*(J_t*v)).
Rows rows_of(const MujocoWorld& w, const std::vector<PairContact>& contacts,
             const std::vector<double>& inv_mass, const Eigen::VectorXd& qvel) {
  const auto nv = qvel.size();
  const MujocoSoftContact& s = w.contact;
  const std::size_t per = s.pyramidal ? 4 : 3;
  Rows rows;
  rows.J = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(per * contacts.size()), nv);
  rows.D.resize(static_cast<Eigen::Index>(per * contacts.size()));
  rows.aref.resize(static_cast<Eigen::Index>(per * contacts.size()));
  rows.elliptic = !s.pyramidal;
  // getsolparam: a mixed solref format is replaced by the default; refsafe keeps a standard time
  // constant at 2h at least; solimp clamped; flat impedance. mj_makeImpedance: K and B from the
  // standard (timeconst, dampratio) or the direct (-stiffness, -damping) format.
  if ((s.solref[0] > 0) != (s.solref[1] > 0))
    throw std::invalid_argument("MuJoCo's re-solve takes no mixed solref format");
  const bool standard = s.solref[0] > 0;
  const double tc = standard ? std::max(s.solref[0], 2 * w.h) : s.solref[0];
  const double dmin = std::clamp(s.solimp[0], 0.0001, 0.9999);
  const double dmax = std::clamp(s.solimp[1], 0.0001, 0.9999);
  if (dmin != dmax && s.solimp[2] > kMinVal)
    throw std::invalid_argument("MuJoCo's re-solve takes a flat impedance (solimp[0] = solimp[1])");
  const double imp = 0.5 * (dmin + dmax);
  const double K = standard
                       ? 1 / std::max(kMinVal, dmax * dmax * tc * tc * s.solref[1] * s.solref[1])
                       : -tc / std::max(kMinVal, dmax * dmax);
  const double B =
      standard ? 2 / std::max(kMinVal, dmax * tc) : -s.solref[1] / std::max(kMinVal, dmax);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const PairContact& pc = contacts[c];
    Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(3, nv), dif = Eigen::MatrixXd::Zero(3, nv);
    double tran = 0;  // the bodies' translational invweight0: 1/m each, a static body none
    for (const Geom* g : {pc.geom1, pc.geom2}) {
      if (g->body < 0) continue;
      add_point_jacobian(dif, pc.c.pos, *g, g == pc.geom2 ? 1.0 : -1.0);
      tran += inv_mass[static_cast<std::size_t>(g->body)];
    }
    for (int r = 0; r < 3; ++r)
      for (Eigen::Index col = 0; col < nv; ++col)
        jac(r, col) = pc.c.frame[3 * r + 0] * dif(0, col) + pc.c.frame[3 * r + 1] * dif(1, col) +
                      pc.c.frame[3 * r + 2] * dif(2, col);
    if (rows.elliptic) {
      const double r0 = std::max(kMinVal, (1 - imp) * tran / imp);
      const double r1 = r0 / std::max(kMinVal, s.impratio);
      rows.mu_reg.push_back(pc.mu * std::sqrt(r1 / r0));
      rows.friction.push_back(pc.mu);
      for (int k = 0; k < 3; ++k) {
        const auto row = static_cast<Eigen::Index>(3 * c + static_cast<std::size_t>(k));
        rows.J.row(row) = jac.row(k);
        rows.D(row) = 1 / (k == 0 ? r0 : r1);
        const double vel = rows.J.row(row).dot(qvel);
        rows.aref(row) = k == 0 ? -B * vel - K * imp * pc.c.dist : -B * vel;
      }
      continue;
    }
    const double diag = tran + pc.mu * pc.mu * tran;
    const double r0 = std::max(kMinVal, (1 - imp) * diag / imp);
    const double r1 = r0 / std::max(kMinVal, s.impratio);
    const double mu_reg = pc.mu * std::sqrt(r1 / r0);
    const double rpy = 2 * mu_reg * mu_reg * r0;
    for (int edge = 0; edge < 4; ++edge) {
      const auto row = static_cast<Eigen::Index>(4 * c + edge);
      const int t = 1 + edge / 2;
      const double sign = edge % 2 == 0 ? pc.mu : -pc.mu;
      rows.J.row(row) = jac.row(0) + jac.row(t) * sign;
      rows.D(row) = 1 / rpy;
      const double vel = rows.J.row(row).dot(qvel);
      rows.aref(row) = -B * vel - K * imp * pc.c.dist;
    }
  }
  return rows;
}

// The minimiser along a + alpha*p of the problem's cost: its derivative in alpha is piecewise
// linear and increasing, zero where the returned alpha is.
double exact_line_search(const Eigen::VectorXd& a, const Eigen::VectorXd& p,
                         const Eigen::VectorXd& a0, const Eigen::MatrixXd& M, const Rows& rows) {
  const Eigen::VectorXd jar = rows.J * a - rows.aref;
  const Eigen::VectorXd jp = rows.J * p;
  const Eigen::VectorXd Mp = M * p;
  double c0 = Mp.dot(a - a0), c1 = Mp.dot(p);
  std::vector<std::pair<double, Eigen::Index>> breaks;
  for (Eigen::Index i = 0; i < jar.size(); ++i) {
    const bool active = jar(i) < 0 || (jar(i) == 0 && jp(i) < 0);
    if (active) {
      c0 += rows.D(i) * jp(i) * jar(i);
      c1 += rows.D(i) * jp(i) * jp(i);
    }
    if (jp(i) != 0 && -jar(i) / jp(i) > 0) breaks.emplace_back(-jar(i) / jp(i), i);
  }
  std::sort(breaks.begin(), breaks.end());
  for (const auto& [at, i] : breaks) {
    if (c1 > 0 && -c0 / c1 <= at) return std::max(0.0, -c0 / c1);
    // Row i changes side at `at`: entering adds its term, leaving removes it.
    const double sign = jp(i) < 0 ? 1.0 : -1.0;
    c0 += sign * rows.D(i) * jp(i) * jar(i);
    c1 += sign * rows.D(i) * jp(i) * jp(i);
  }
  return -c0 / c1;
}

// A Newton step this small relative to the acceleration is rounding (about 100 ulps).
constexpr double kStepRounding = 1e-14;

struct Solution {
  Eigen::VectorXd qacc;
  Eigen::VectorXd force;  // efc_force: -D*jar on active rows
  int iterations = 0;
};

// Newton's method on the piecewise quadratic cost with exact line searches: done when a full step
// lands on a point whose active rows are the ones it assumed (the quadratic piece's minimum lies
// inside the piece: the global minimum of the convex cost).
Solution solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& a0, const Rows& rows) {
  Solution s{a0, Eigen::VectorXd::Zero(rows.J.rows())};
  for (s.iterations = 1; s.iterations <= 100; ++s.iterations) {
    const Eigen::VectorXd jar = rows.J * s.qacc - rows.aref;
    Eigen::MatrixXd H = M;
    Eigen::VectorXd g = M * (s.qacc - a0);
    std::vector<bool> active(static_cast<std::size_t>(jar.size()));
    for (Eigen::Index i = 0; i < jar.size(); ++i) {
      active[static_cast<std::size_t>(i)] = jar(i) < 0;
      if (jar(i) >= 0) continue;
      H += rows.D(i) * rows.J.row(i).transpose() * rows.J.row(i);
      g += rows.D(i) * jar(i) * rows.J.row(i).transpose();
    }
    const Eigen::VectorXd p = -H.ldlt().solve(g);
    if (p.cwiseAbs().maxCoeff() == 0.0) break;
    const double alpha = exact_line_search(s.qacc, p, a0, M, rows);
    s.qacc += alpha * p;
    // Rows at a kink of the cost (J_i*a = aref_i) may flip with the last bits: a step that moves
    // nothing beyond rounding ends the search.
    if ((alpha * p).cwiseAbs().maxCoeff() <=
        kStepRounding * std::max(1.0, s.qacc.cwiseAbs().maxCoeff()))
      break;
    const Eigen::VectorXd after = rows.J * s.qacc - rows.aref;
    bool same = alpha == 1.0;
    for (Eigen::Index i = 0; i < after.size() && same; ++i)
      same = (after(i) < 0) == active[static_cast<std::size_t>(i)];
    if (same) break;
  }
  if (s.iterations > 100) throw std::runtime_error("MuJoCo's re-solve did not converge");
  const Eigen::VectorXd jar = rows.J * s.qacc - rows.aref;
  for (Eigen::Index i = 0; i < jar.size(); ++i) s.force(i) = jar(i) < 0 ? -rows.D(i) * jar(i) : 0.0;
  return s;
}

// One elliptic contact's cost s(jar) as mj_constraintUpdate zones it, with its gradient and
// Hessian in jar. U = (mu_r*jar_n, f*jar_t1, f*jar_t2), N = U_0, T = |U_1..2|: nothing above the
// cone (N >= mu_r*T), the rows' quadratic below its dual (mu_r*N + T <= 0), and in between
// 1/2 Dm (N - mu_r*T)^2 with Dm = D_0/(mu_r^2 (1 + mu_r^2)).
struct ConeCost {
  double cost = 0.0;
  Eigen::Vector3d grad = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hess = Eigen::Matrix3d::Zero();
};

ConeCost cone_cost(const Eigen::Vector3d& jar, const Eigen::Vector3d& D, double mu, double f) {
  ConeCost c;
  const double N = jar(0) * mu, u1 = jar(1) * f, u2 = jar(2) * f;
  const double T = std::hypot(u1, u2);
  if (N >= mu * T || (T <= 0 && N >= 0)) return c;
  if (mu * N + T <= 0 || (T <= 0 && N < 0)) {
    c.cost = 0.5 * (D.array() * jar.array() * jar.array()).sum();
    c.grad = D.cwiseProduct(jar);
    c.hess = D.asDiagonal();
    return c;
  }
  const double Dm = D(0) / (mu * mu * (1 + mu * mu));
  const double sN = N - mu * T;
  const Eigen::Vector3d ds(mu, -mu * f * u1 / T, -mu * f * u2 / T);
  Eigen::Matrix3d hs = Eigen::Matrix3d::Zero();
  const Eigen::Vector2d u(u1, u2);
  hs.block<2, 2>(1, 1) =
      -mu * f * f * (Eigen::Matrix2d::Identity() / T - u * u.transpose() / (T * T * T));
  c.cost = 0.5 * Dm * sN * sN;
  c.grad = Dm * sN * ds;
  c.hess = Dm * (ds * ds.transpose() + sN * hs);
  return c;
}

// The elliptic problem's cost, gradient and Hessian at a.
struct Objective {
  double cost = 0.0;
  Eigen::VectorXd grad;
  Eigen::MatrixXd hess;
};

Objective elliptic_objective(const Eigen::MatrixXd& M, const Eigen::VectorXd& a0, const Rows& rows,
                             const Eigen::VectorXd& a, bool with_hessian) {
  const Eigen::VectorXd d = a - a0;
  Objective o{0.5 * d.dot(M * d), M * d, with_hessian ? M : Eigen::MatrixXd()};
  const Eigen::VectorXd jar = rows.J * a - rows.aref;
  for (std::size_t c = 0; c < rows.mu_reg.size(); ++c) {
    const auto r = static_cast<Eigen::Index>(3 * c);
    const ConeCost k =
        cone_cost(jar.segment<3>(r), rows.D.segment<3>(r), rows.mu_reg[c], rows.friction[c]);
    const auto Jc = rows.J.middleRows(r, 3);
    o.cost += k.cost;
    o.grad += Jc.transpose() * k.grad;
    if (with_hessian) o.hess += Jc.transpose() * k.hess * Jc;
  }
  return o;
}

// The elliptic cost's first and second derivatives along p at a + alpha*p.
std::pair<double, double> along(const Eigen::MatrixXd& M, const Eigen::VectorXd& a0,
                                const Rows& rows, const Eigen::VectorXd& a,
                                const Eigen::VectorXd& p, double alpha) {
  const Eigen::VectorXd x = a + alpha * p;
  const Eigen::VectorXd Mp = M * p;
  double slope = Mp.dot(x - a0), curvature = Mp.dot(p);
  const Eigen::VectorXd jar = rows.J * x - rows.aref;
  const Eigen::VectorXd jp = rows.J * p;
  for (std::size_t c = 0; c < rows.mu_reg.size(); ++c) {
    const auto r = static_cast<Eigen::Index>(3 * c);
    const ConeCost k =
        cone_cost(jar.segment<3>(r), rows.D.segment<3>(r), rows.mu_reg[c], rows.friction[c]);
    slope += k.grad.dot(jp.segment<3>(r));
    curvature += jp.segment<3>(r).dot(k.hess * jp.segment<3>(r));
  }
  return {slope, curvature};
}

// The minimiser of the cost along a + alpha*p (alpha >= 0): the root of its increasing slope, by
// Newton steps kept inside a bracket that bisection shrinks when a step would leave it.
double line_search(const Eigen::MatrixXd& M, const Eigen::VectorXd& a0, const Rows& rows,
                   const Eigen::VectorXd& a, const Eigen::VectorXd& p) {
  double lo = 0.0, hi = 1.0;
  while (along(M, a0, rows, a, p, hi).first < 0 && hi < 1e6) hi *= 2;
  double alpha = std::min(1.0, hi);
  for (int k = 0; k < 100; ++k) {
    const auto [slope, curvature] = along(M, a0, rows, a, p, alpha);
    if (slope == 0) return alpha;
    (slope < 0 ? lo : hi) = alpha;
    const double newton = alpha - slope / curvature;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    if (std::abs(next - alpha) <= 1e-16 * std::max(alpha, 1e-300)) return next;
    alpha = next;
  }
  return alpha;
}

// Newton's method on the elliptic cost (convex, its gradient continuous across the zones), each
// step's length the root of the cost's slope along it.
Solution solve_elliptic(const Eigen::MatrixXd& M, const Eigen::VectorXd& a0, const Rows& rows) {
  Solution s{a0, Eigen::VectorXd::Zero(rows.J.rows())};
  for (s.iterations = 1; s.iterations <= 100; ++s.iterations) {
    const Objective o = elliptic_objective(M, a0, rows, s.qacc, true);
    const Eigen::VectorXd p = -o.hess.ldlt().solve(o.grad);
    if (!(p.cwiseAbs().maxCoeff() > 0.0)) break;
    const double alpha = line_search(M, a0, rows, s.qacc, p);
    s.qacc += alpha * p;
    if ((alpha * p).cwiseAbs().maxCoeff() <=
        kStepRounding * std::max(1.0, s.qacc.cwiseAbs().maxCoeff()))
      break;
  }
  if (s.iterations > 100) throw std::runtime_error("MuJoCo's re-solve did not converge");
  // efc_force = -ds/djar, per contact.
  const Eigen::VectorXd jar = rows.J * s.qacc - rows.aref;
  for (std::size_t c = 0; c < rows.mu_reg.size(); ++c) {
    const auto r = static_cast<Eigen::Index>(3 * c);
    s.force.segment<3>(r) =
        -cone_cost(jar.segment<3>(r), rows.D.segment<3>(r), rows.mu_reg[c], rows.friction[c]).grad;
  }
  return s;
}

// The world's constant parts: the dof blocks, masses and damping.
struct Model {
  const MujocoWorld& world;
  std::vector<int> block;  // dof block of each body, -1 for a static one
  std::vector<double> inv_mass;
  Eigen::VectorXd mass, damp;
  Eigen::MatrixXd M;
  bool damped = false;
};

Model model_of(const MujocoWorld& world) {
  Model m{world, std::vector<int>(world.bodies.size(), -1), {}, {}, {}, {}, false};
  int dynamic = 0;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (!world.bodies[i].is_static) {
      m.block[i] = dynamic++;
      m.inv_mass.push_back(1 / world.bodies[i].mass);
    }
  // M = diag(m, m, m, Ixx, Iyy, Izz) per body (the free joint's rotational dofs are body axes, the
  // centre of mass at the body's origin); B the dofs' damping.
  m.mass.resize(6 * dynamic);
  m.damp.resize(6 * dynamic);
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    if (m.block[i] < 0) continue;
    const MujocoBody& b = world.bodies[i];
    const Eigen::Index o = 6 * m.block[i];
    for (int k = 0; k < 3; ++k) {
      m.mass(o + k) = b.mass;
      m.mass(o + 3 + k) = b.inertia[k];
      m.damp(o + k) = b.damping;
      m.damp(o + 3 + k) = b.angular_damping[k];
    }
  }
  m.M = m.mass.asDiagonal();
  m.damped = (m.damp.array() > 0).any();
  return m;
}

struct StepResult {
  std::vector<Pose> poses;
  MujocoStepInfo info;
  std::vector<int> undecided;  // pairs whose face or edge branch the last bits decide
};

// One mj_step from `poses`, the pairs numbered in `flip` taking their other branch.
StepResult step_once(const Model& model, const std::vector<Pose>& poses,
                     const std::vector<int>& flip) {
  const MujocoWorld& world = model.world;
  const Eigen::Index nv = model.mass.size();
  StepResult out{poses, {}, {}};
  Eigen::VectorXd qvel(nv), qfrc(nv);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (model.block[i] < 0) continue;
    const MujocoBody& b = world.bodies[i];
    const Pose& p = poses[i];
    const Eigen::Index o = 6 * model.block[i];
    const Vec3 w(p.w[0], p.w[1], p.w[2]);
    const Vec3 bias = w.cross(b.inertia.cwiseProduct(w));  // mj_rne's w x I*w, body axes
    for (int k = 0; k < 3; ++k) {
      qvel(o + k) = p.vel[k];
      qvel(o + 3 + k) = p.w[k];
      qfrc(o + k) = b.mass * world.gravity[k] - b.damping * p.vel[k];
      qfrc(o + 3 + k) = -bias[k] - b.angular_damping[k] * p.w[k];
    }
  }
  const Eigen::VectorXd a0 = qfrc.cwiseQuotient(model.mass);
  Eigen::VectorXd qacc = a0;
  Eigen::VectorXd qfrc_constraint = Eigen::VectorXd::Zero(nv);
  if (world.contacts) {
    const std::vector<Geom> geoms = geoms_of(world, poses, model.block);
    const std::vector<PairContact> contacts = collide(geoms, flip, &out.undecided);
    out.info.contacts = static_cast<int>(contacts.size());
    if (!contacts.empty()) {
      const Rows rows = rows_of(world, contacts, model.inv_mass, qvel);
      const Solution s =
          rows.elliptic ? solve_elliptic(model.M, a0, rows) : solve(model.M, a0, rows);
      qacc = s.qacc;
      qfrc_constraint = rows.J.transpose() * s.force;
      out.info.newton_iterations = s.iterations;
      out.info.active_rows = static_cast<int>((s.force.array() != 0).count());
    }
  }
  // mj_Euler with damping: (M + h*B) qacc = qfrc_smooth + qfrc_constraint.
  if (model.damped)
    qacc = (qfrc + qfrc_constraint).cwiseQuotient(model.mass + world.h * model.damp);
  // mj_advance: qvel += h*qacc; mj_integratePos: x += h*v, q <- q*exp(h*w/2).
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (model.block[i] < 0) continue;
    Pose& p = out.poses[i];
    const Eigen::Index o = 6 * model.block[i];
    for (int k = 0; k < 3; ++k) {
      p.vel[k] += world.h * qacc(o + k);
      p.w[k] += world.h * qacc(o + 3 + k);
    }
    for (int k = 0; k < 3; ++k) p.pos[k] += world.h * p.vel[k];
    quat_integrate(p.quat, p.w, world.h);
  }
  return out;
}

// How far `poses` are from the run's positions after step n (summed over the bodies).
double distance_to_run(const std::vector<Pose>& poses, const MujocoSteer& steer, std::int64_t n) {
  double d = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Vec3& x = steer.run[static_cast<std::size_t>(n) * poses.size() + i].position;
    d += std::hypot(poses[i].pos[0] - x[0], poses[i].pos[1] - x[1], poses[i].pos[2] - x[2]);
  }
  return d;
}

// The step from `poses` with each undecided pair on the branch that brings the step closest to the
// run (one pair at a time, in order), or as MuJoCo decides on these poses without a run.
StepResult steered_step(const Model& model, const std::vector<Pose>& poses,
                        const MujocoSteer* steer, std::int64_t n) {
  StepResult best = step_once(model, poses, {});
  const bool has_run = steer && static_cast<std::size_t>(n + 1) * poses.size() <= steer->run.size();
  if (!has_run || best.undecided.empty()) return best;
  std::vector<int> flip;
  double best_distance = distance_to_run(best.poses, *steer, n);
  for (const int pair : std::vector<int>(best.undecided)) {
    flip.push_back(pair);
    StepResult trial = step_once(model, poses, flip);
    const double d = distance_to_run(trial.poses, *steer, n);
    if (d < best_distance) {
      best_distance = d;
      best = std::move(trial);
    } else {
      flip.pop_back();
    }
  }
  return best;
}

}  // namespace

std::vector<MujocoState> mujoco_replay(const MujocoWorld& world, std::int64_t steps,
                                       const MujocoSteer* steer,
                                       std::vector<MujocoStepInfo>* info) {
  if (steer && steer->run.size() % std::max<std::size_t>(world.bodies.size(), 1) != 0)
    throw std::invalid_argument("MuJoCo's re-solve: the run's states are not whole steps");
  const Model model = model_of(world);
  std::vector<Pose> poses(world.bodies.size());
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const MujocoBody& b = world.bodies[i];
    Pose& p = poses[i];
    for (int k = 0; k < 3; ++k) {
      p.pos[k] = b.position[k];
      p.vel[k] = b.is_static ? 0.0 : b.velocity[k];
      p.w[k] = b.is_static ? 0.0 : b.angular_velocity_body[k];
    }
    p.quat[0] = b.orientation.w(), p.quat[1] = b.orientation.x();
    p.quat[2] = b.orientation.y(), p.quat[3] = b.orientation.z();
  }
  std::vector<MujocoState> out;
  out.reserve(poses.size() * static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)));
  for (std::int64_t n = 1; n <= steps; ++n) {
    StepResult r = steered_step(model, poses, steer, n);
    poses = std::move(r.poses);
    for (const Pose& p : poses)
      out.push_back({Vec3(p.pos[0], p.pos[1], p.pos[2]),
                     Quat(p.quat[0], p.quat[1], p.quat[2], p.quat[3]),
                     Vec3(p.vel[0], p.vel[1], p.vel[2]), Vec3(p.w[0], p.w[1], p.w[2])});
    r.info.undecided_pairs = static_cast<int>(r.undecided.size());
    if (info) info->push_back(r.info);
  }
  return out;
}

}  // namespace dropcheck
