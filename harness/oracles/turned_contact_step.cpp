#include "harness/oracles/turned_contact_step.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "harness/core/rotation_law.hpp"

namespace dropcheck {
namespace {

using Real = long double;
using V = Eigen::Matrix<Real, 3, 1>;
using M3 = Eigen::Matrix<Real, 3, 3>;
using Q = Eigen::Quaternion<Real>;

constexpr int kMaxAmbiguous = 12;

// A corner of the box against one static box's face: how far it is below the face (>= 0 in
// contact), and whether its side is decided.
struct Corner {
  V point;
  Real below = 0;
  bool ambiguous = false;
};

// One static box the body's bounding box overlaps: the face's normal, and the corners within it.
struct Face {
  std::size_t other = 0;
  V normal = V::Zero();
  std::vector<Corner> corners;
};

// One contact as the law resolves it (a Face with its corners decided).
struct FaceContact {
  V normal = V::Zero();
  Real depth = 0;
  V arm = V::Zero();  // 0: through the centre
  Real approach = 0;
};

// The body's state in long double.
struct Box {
  V x, v, w;
  Q q;
  V half, inertia;
  Real mass = 1;
  bool turned = false;  // turned or turning at the step start: the impulse acts at a point
};

Box box_at(const dropcheck::Body& b, const BodyState& s, const RotationState& r) {
  Box out;
  out.x = s.position.cast<Real>();
  out.v = s.velocity.cast<Real>();
  out.q = r.orientation.cast<Real>();
  out.w = r.angular_velocity.cast<Real>();
  out.half = b.half_extents.cast<Real>();
  out.inertia = inertia_of(b).cast<Real>();
  out.mass = b.mass;
  out.turned =
      r.orientation.coeffs() != Quat::Identity().coeffs() || !r.angular_velocity.isZero(0.0);
  return out;
}

// The face of static box (centre c, half extents hb) that the body's bounding box overlaps least,
// with the corners in it, or nothing when the boxes are apart by more than `decide`. An unturned,
// still body has one "corner": its centre, pushed through (the flat law).
std::optional<Face> face_of(const Box& b, std::size_t other, const V& c, const V& hb, Real decide) {
  const M3 R = b.q.toRotationMatrix();
  const V reach = b.turned ? V(R.cwiseAbs() * b.half) : b.half;
  int axis = -1;
  Real least = 0;
  for (int i = 0; i < 3; ++i) {
    const Real overlap = (reach[i] + hb[i]) - std::abs(b.x[i] - c[i]);
    if (overlap < (b.turned ? -decide : Real(0))) return std::nullopt;
    if (axis < 0 || overlap < least) {
      axis = i;
      least = overlap;
    }
  }
  Face f;
  f.other = other;
  f.normal[axis] = b.x[axis] >= c[axis] ? Real(1) : Real(-1);
  if (!b.turned) {
    f.corners.push_back({b.x, least, false});
    return f;
  }
  for (int k = 0; k < 8; ++k) {
    const V corner(k & 1 ? b.half.x() : -b.half.x(), k & 2 ? b.half.y() : -b.half.y(),
                   k & 4 ? b.half.z() : -b.half.z());
    const V p = b.x + R * corner;
    const V local = p - c;
    bool within = true;
    for (int i = 0; i < 3; ++i)
      if (i != axis && std::abs(local[i]) > hb[i]) within = false;
    if (!within) continue;
    const Real below = hb[axis] - f.normal[axis] * local[axis];
    if (below <= -decide) continue;
    f.corners.push_back({p, below, below < decide});
  }
  return f;
}

// The contact of `f` with the corners chosen by `bits` (one bit per ambiguous corner, from
// `next`), or nothing when no corner is in it.
std::optional<FaceContact> decide_contact(const Box& b, const Face& f, unsigned bits, int& next,
                                          int& count) {
  FaceContact c;
  c.normal = f.normal;
  V sum = V::Zero();
  int in = 0;
  for (const Corner& k : f.corners) {
    const bool touching = k.ambiguous ? ((bits >> next++) & 1u) != 0 : k.below >= 0;
    if (!touching) continue;
    c.depth = std::max(c.depth, std::max(k.below, Real(0)));
    sum += k.point;
    ++in;
  }
  if (in == 0) return std::nullopt;
  count += in;
  if (b.turned) c.arm = sum / Real(in) - b.x;
  c.approach = -(b.v + b.w.cross(c.arm)).dot(c.normal);
  return c;
}

// The normal impulse, then friction against the slip, at the contact's point (the header's K).
void resolve(Box& b, const FaceContact& c, Real mu, Real e) {
  const M3 R = b.q.toRotationMatrix();
  const auto turn_per = [&](const V& j) -> V {
    return R * (R.transpose() * c.arm.cross(j)).cwiseQuotient(b.inertia);
  };
  const auto response = [&](const V& d) -> V { return d / b.mass + turn_per(d).cross(c.arm); };
  const auto apply = [&](const V& j) {
    b.v += j / b.mass;
    b.w += turn_per(j);
  };
  const Real target = c.approach > 0 ? e * c.approach : Real(0);
  const Real j_n = std::max(target - (b.v + b.w.cross(c.arm)).dot(c.normal), Real(0)) /
                   c.normal.dot(response(c.normal));
  apply(j_n * c.normal);
  const V u = b.v + b.w.cross(c.arm);
  const V slip = u - u.dot(c.normal) * c.normal;
  const Real speed = slip.norm();
  if (speed == 0) return;
  const V t = slip / speed;
  apply(-std::min(speed / t.dot(response(t)), mu * j_n) * t);
}

}  // namespace

TurnedContactScope turned_contact_scope(const Scene& scene, const EngineInfo& info, double h) {
  TurnedContactScope s;
  const auto refuse = [&](std::string why) {
    s.not_judged = std::move(why);
    return s;
  };
  if (!scene.forces.empty() || !scene.torques.empty())
    return refuse("forces or torques act (the law is replayed without them)");
  if (info.law != Law(DampingOrder::AfterForces))
    return refuse("the engine's damping is not after the forces");
  int dynamic = 0;
  for (const dropcheck::Body& b : scene.bodies) {
    if (b.shape != Shape::box) return refuse("a sphere (the law turns boxes)");
    dynamic += b.is_static ? 0 : 1;
  }
  if (dynamic != 1) return refuse("not one dynamic box over static boxes");
  const Material m = scene_material(scene);
  s.setup = {&scene,
             info.law,
             info.rotation_law,
             h,
             decay_per_step(scene, h),
             angular_decay_per_step(scene, h),
             m.friction.value_or(0.0),
             m.restitution.value_or(0.0)};
  return s;
}

std::vector<TurnedCandidate> turned_contact_step(const TurnedContactSetup& setup,
                                                 std::span<const BodyState> linear,
                                                 std::span<const RotationState> rotation,
                                                 double decide) {
  const Scene& scene = *setup.scene;
  const std::size_t n = scene.bodies.size();
  std::size_t dyn = 0;
  std::vector<std::size_t> statics;
  for (std::size_t i = 0; i < n; ++i)
    if (scene.bodies[i].is_static)
      statics.push_back(i);
    else
      dyn = i;
  // Contacts resolve in the order of their static box's height (then body order).
  std::stable_sort(statics.begin(), statics.end(), [&](std::size_t a, std::size_t b) {
    return linear[a].position.y() < linear[b].position.y();
  });
  const Box start = box_at(scene.bodies[dyn], linear[dyn], rotation[dyn]);
  std::vector<Face> faces;
  int ambiguous = 0;
  for (std::size_t s : statics)
    if (auto f = face_of(start, s, linear[s].position.cast<Real>(),
                         scene.bodies[s].half_extents.cast<Real>(), decide)) {
      for (const Corner& k : f->corners) ambiguous += k.ambiguous ? 1 : 0;
      faces.push_back(std::move(*f));
    }
  if (ambiguous > kMaxAmbiguous)  // too many to try: each is decided by its sign
    for (Face& f : faces)
      for (Corner& k : f.corners) k.ambiguous = false;
  const int tried = std::min(ambiguous, kMaxAmbiguous);

  const Real h = setup.h;
  const V g = scene.world.gravity.cast<Real>();
  const bool turns = !start.w.isZero(0);
  std::vector<TurnedCandidate> out;
  for (unsigned bits = 0; bits < (1u << tried); ++bits) {
    Box b = start;
    TurnedCandidate c;
    std::vector<FaceContact> contacts;
    int next = 0;
    for (const Face& f : faces)
      if (auto k = decide_contact(b, f, bits, next, c.contacts)) contacts.push_back(*k);
    // The free step (the engine's members), then the contacts, then the pose.
    const M3 R = b.q.toRotationMatrix();
    b.v = Real(setup.phi) * (b.v + g * h);
    if (turns)
      b.w = Real(setup.phi_a) *
            rotation_detail::gyroscopic_update(setup.rotation.gyroscopic, R, b.inertia, h, b.w);
    for (const FaceContact& k : contacts) resolve(b, k, setup.friction, setup.restitution);
    b.x += h * b.v;
    if (turns || !b.w.isZero(0))
      b.q = rotation_detail::orientation_update(setup.rotation.orientation, b.q, b.w, h);
    for (const FaceContact& k : contacts) b.x += k.depth * k.normal;
    c.linear.assign(linear.begin(), linear.end());
    c.rotation.assign(rotation.begin(), rotation.end());
    c.linear[dyn] = {b.x.cast<double>(), b.v.cast<double>()};
    c.rotation[dyn] = {b.q.cast<double>(), b.w.cast<double>()};
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace dropcheck
