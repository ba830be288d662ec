#include "harness/oracles/stack.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/landing.hpp"

namespace dropcheck {
namespace {

// `upper`'s centre lies strictly inside `lower`'s top face (x-z): a centre on an edge balances
// between two columns, and neither carries its load alone.
bool over_body(const Body& upper, const Body& lower) {
  return std::abs(upper.position.x() - lower.position.x()) < lower.half_extents.x() &&
         std::abs(upper.position.z() - lower.position.z()) < lower.half_extents.z();
}

// The x-z footprints of a and b overlap (open rectangles: boxes that only touch at an edge do not).
bool overlaps(const Body& a, const Body& b) {
  return std::abs(a.position.x() - b.position.x()) < a.half_extents.x() + b.half_extents.x() &&
         std::abs(a.position.z() - b.position.z()) < a.half_extents.z() + b.half_extents.z();
}

// Every body that shares a member's footprint above the floor is a member: no load the column does
// not count rests on it, and nothing else stands in its way.
bool closed(const Scene& scene, const StackSetup& s) {
  const double floor_top = top_of(scene.bodies[s.floor]);
  for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
    if (j == s.floor || top_of(scene.bodies[j]) <= floor_top) continue;
    const bool member = std::any_of(s.levels.begin(), s.levels.end(),
                                    [&](const StackLevel& l) { return l.body == j; });
    if (member) continue;
    for (const StackLevel& l : s.levels)
      if (overlaps(scene.bodies[j], scene.bodies[l.body])) return false;
  }
  return true;
}

// A body a stack may hold: a dynamic box at rest, pushed by nothing.
bool stackable(const Scene& scene, std::size_t i) {
  const Body& b = scene.bodies[i];
  return !b.is_static && b.shape == Shape::box && b.velocity == Vec3::Zero() && !pushed(scene, i);
}

// The normal velocity a unit impulse at a corner (+-c.x, +-c.z from the body's centre, on its top
// or bottom face) makes there through the body's rotation: with n = y, r x n = (-r_z, 0, r_x).
double corner_turn(const Body& b, const Vec3& c) {
  const Vec3 moments = inertia_of(b);
  return c.z() * c.z() / moments.x() + c.x() * c.x() / moments.z();
}

}  // namespace

std::vector<StackSetup> stack_setups(const Scene& scene) {
  std::vector<StackSetup> out;
  const Vec3& g = scene.world.gravity;
  if (!floor_contact(scene) || !level_gravity(scene)) return out;
  // A column starts with a body resting on its floor (the landing oracle's floor); the next level
  // is the lowest stackable body over the level under it, with its bottom at or above that top.
  for (const LandingSetup& l : landing_setups(scene)) {
    const Body& first = scene.bodies[l.body];
    if (!stackable(scene, l.body) || std::abs(first.position.y() - l.rest_height) > 1e-9) continue;
    StackSetup s{l.body,
                 l.floor,
                 l.floor_top,
                 -g.y(),
                 scene.world.damping_rate,
                 {{l.body, 1, l.rest_height, first.mass, 0.0, 0.0,
                   corner_turn(first, first.half_extents), true, bottom_of(first) - l.floor_top}}};
    for (;;) {
      const StackLevel& under_level = s.levels.back();
      const Body& under = scene.bodies[under_level.body];
      long next = -1;
      for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
        const Body& b = scene.bodies[j];
        if (!stackable(scene, j) || !over_body(b, under) || bottom_of(b) < top_of(under)) continue;
        if (next < 0 || b.position.y() < scene.bodies[static_cast<std::size_t>(next)].position.y())
          next = static_cast<long>(j);
      }
      if (next < 0) break;
      const Body& b = scene.bodies[static_cast<std::size_t>(next)];
      const Vec3 corner = b.half_extents.cwiseMin(under.half_extents);
      s.levels.push_back(
          {static_cast<std::size_t>(next), under_level.level + 1,
           under_level.rest_height + under.half_extents.y() + b.half_extents.y(), b.mass, 0.0,
           under.mass, corner_turn(b, corner) + corner_turn(under, corner),
           b.position.x() == under.position.x() && b.position.z() == under.position.z(),
           bottom_of(b) - top_of(under)});
    }
    if (s.levels.size() < 2 || !closed(scene, s)) continue;
    double load = 0.0;  // top down: each body and everything above it
    for (auto it = s.levels.rbegin(); it != s.levels.rend(); ++it) it->load = load += it->mass;
    out.push_back(std::move(s));
  }
  return out;
}

namespace {

// The impulses X_k >= 0 of the contacts found (`found`) that meet every row's target
// (relative_cfm_column): rows k of M*X = b, M tridiagonal (row k couples X_(k-1), X_k, X_(k+1)
// through the bodies k - 1 and k it joins), solved with the contacts whose impulse would pull left
// out, one at a time (the most negative first) until none pulls. A contact left out has the row
// X_k = 0.
std::vector<double> column_impulses(const std::vector<double>& mass,
                                    const std::vector<double>& soft, const std::vector<double>& b,
                                    std::vector<bool> found) {
  const auto n = static_cast<Eigen::Index>(mass.size());
  for (Eigen::Index pass = 0; pass <= n; ++pass) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!found[k]) continue;
      m(k, k) = 1.0 / mass[k] + (k > 0 ? 1.0 / mass[k - 1] : 0.0) + soft[k];
      if (k > 0 && found[k - 1]) m(k, k - 1) = -1.0 / mass[k - 1];
      if (k + 1 < n && found[k + 1]) m(k, k + 1) = -1.0 / mass[k];
      rhs[k] = b[k];
    }
    const Eigen::VectorXd x = m.ldlt().solve(rhs);  // symmetric positive definite
    // The found contact whose impulse pulls most; none: done. At most n passes (each drops one).
    Eigen::Index worst = n;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!found[k]) continue;
      if (!std::isfinite(x[k]))
        throw std::invalid_argument("relative_cfm_column: a non-finite impulse");
      if (x[k] < 0.0 && (worst == n || x[k] < x[worst])) worst = k;
    }
    if (worst == n) return {x.data(), x.data() + n};
    found[worst] = false;
  }
  throw std::logic_error("column_impulses: more passes than contacts");
}

}  // namespace

ColumnPath relative_cfm_column(const StackSetup& setup, const RelativeCfm& law, double h,
                               std::int64_t steps, std::int64_t from) {
  if (!(law.cfm > 0.0)) throw std::invalid_argument("relative_cfm_column: a law without CFM");
  const std::size_t n = setup.levels.size();
  std::vector<double> mass, soft, half;  // half: each box's half height, from the rest heights
  for (std::size_t k = 0; k < n; ++k) {
    const StackLevel& l = setup.levels[k];
    if (!l.centred) throw std::invalid_argument("relative_cfm_column: a level not centred");
    mass.push_back(l.mass);
    const double a = 1.0 / l.mass + (l.mass_below > 0.0 ? 1.0 / l.mass_below : 0.0) + l.corner_turn;
    soft.push_back(law.cfm * a / 4.0);
    half.push_back(k == 0 ? l.rest_height - setup.floor_top
                          : l.rest_height - setup.levels[k - 1].rest_height - half[k - 1]);
  }
  const double phi = std::exp(-setup.damping_rate * h);
  std::vector<double> v(n, 0.0), d(n, 0.0), v_free(n), b(n), lo(n, INFINITY), hi(n, -INFINITY);
  std::vector<bool> found(n);
  ColumnPath path{std::vector<double>(n, 0.0), std::vector<StillFigures>(n), -1};
  for (std::size_t k = 0; k < n; ++k) d[k] = -setup.levels[k].gap;  // dropped: above it
  // Each level's sink below its rest height, and its stillness figures from `from` on.
  const auto watch = [&](std::int64_t step) {
    for (std::size_t k = 0; k < n; ++k) {
      path.sink[k] = d[k] + (k > 0 ? path.sink[k - 1] : 0.0);
      if (path.past_faces < 0 && d[k] >= half[k]) path.past_faces = step;
      if (step < from) continue;
      path.still[k].speed = std::max(path.still[k].speed, std::abs(v[k]));
      lo[k] = std::min(lo[k], -path.sink[k]);
      hi[k] = std::max(hi[k], -path.sink[k]);
      path.still[k].range = hi[k] - lo[k];
    }
  };
  watch(0);
  for (std::int64_t step = 1; step <= steps; ++step) {
    for (std::size_t k = 0; k < n; ++k) v_free[k] = phi * (v[k] - setup.g * h);
    for (std::size_t k = 0; k < n; ++k) {
      found[k] = d[k] >= 0.0;
      const double below = k > 0 ? v_free[k - 1] : 0.0;
      b[k] = std::min(law.erp * d[k] / h, law.max_push) - (v_free[k] - below);
    }
    const std::vector<double> x = column_impulses(mass, soft, b, found);
    for (std::size_t k = 0; k < n; ++k)
      v[k] = v_free[k] + (x[k] - (k + 1 < n ? x[k + 1] : 0.0)) / mass[k];
    for (std::size_t k = 0; k < n; ++k) d[k] -= h * (v[k] - (k > 0 ? v[k - 1] : 0.0));
    watch(step);
  }
  return path;
}

std::string stack_law_text(const EngineInfo& info) {
  if (info.relative_cfm.cfm > 0.0)
    return "a centred column stepped exactly under " + describe(info.relative_cfm);
  return describe(info.stack_law);
}

std::vector<StackPrediction> predict_stack(const StackSetup& setup, const EngineInfo& info,
                                           double h, std::int64_t steps, std::int64_t from) {
  std::vector<StackPrediction> out;
  if (info.relative_cfm.cfm > 0.0) {  // stepped once for every level
    const ColumnPath path = relative_cfm_column(setup, info.relative_cfm, h, steps, from);
    for (std::size_t k = 0; k < setup.levels.size(); ++k)
      out.push_back({.sink = path.sink[k],
                     .exact = true,
                     .still = path.still[k],
                     .past_faces = path.past_faces,
                     .offset = static_cast<double>(k + 1) * info.rest_offset});
    return out;
  }
  StackPrediction p;  // each level adds its lower contact to the ones under it
  for (const StackLevel& l : setup.levels) {
    p.sink += contact_sink(info.stack_law, setup.g * l.load, l.mass, l.mass_below, h);
    p.offset += info.rest_offset;
    const double r =
        l.mass_below > 0.0 ? sweep_residual(info.stack_law, l.load, l.mass_below) : 0.0;
    if (r > p.residual) {  // on the static floor nothing is swept against
      p.residual = r;
      p.load = l.load;
      p.mass = l.mass_below;
    }
    out.push_back(p);
  }
  return out;
}

StackPrediction predict_stack(const StackSetup& setup, std::size_t level, const EngineInfo& info,
                              double h, std::int64_t steps, std::int64_t from) {
  return predict_stack(setup, info, h, steps, from).at(level);
}

}  // namespace dropcheck
