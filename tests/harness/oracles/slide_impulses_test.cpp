// Tests harness/oracles/slide_impulses.cpp against the clamp law, whose impulses are known in
// closed form: a box at rest on its floor is pushed up by exactly m*g*h a step, and a slipping
// step's friction is mu times that against the slip.
#include "harness/oracles/slide_impulses.hpp"

#include <catch2/catch.hpp>
#include <vector>

using namespace dropcheck;

namespace {

// slide_stop's slide: 5 m/s along x, mu = 0.5, g = 9.8, h = 1/60.
SlideSetup slide_stop_setup() {
  return {.body = 0, .v0 = 5.0, .direction = Vec3::UnitX(), .angle = 0.0, .mu = 0.5, .g = 9.8};
}

// The states of `path` (a slide along x, level: no vertical motion).
std::vector<BodyState> level_states(const SlidePath& path) {
  std::vector<BodyState> out;
  for (std::size_t n = 0; n < path.s.size(); ++n)
    out.push_back({Vec3(path.s[n], 0.5, 0.0), Vec3(path.v[n], 0.0, 0.0)});
  return out;
}

constexpr double kSixtieth = 1.0 / 60.0;

}  // namespace

TEST_CASE("the clamp law's impulses are m*g*h up and mu*m*g*h against the slip", "[impulses]") {
  const SlideSetup s = slide_stop_setup();
  const SlidePath law = slide_path(s, FrictionModel::cone, kSixtieth, 100);
  const std::vector<SlideImpulse> k = slide_impulses(level_states(law), s, kSixtieth);
  REQUIRE(k.size() == 100);
  CHECK(k[0].normal == Approx(9.8 * kSixtieth).epsilon(1e-14));
  CHECK(k[0].along == Approx(-0.5 * 9.8 * kSixtieth).epsilon(1e-12));
  CHECK(k[0].across == 0.0);
  const CoulombCertificate c = coulomb_certificate(k, s.mu, s.g, kSixtieth, 0.0);
  CHECK(c.holds);
  // The clamp law stops at step 62 (v0 / (mu*g*h) = 61.2): 61 slipping steps, the rest held.
  CHECK(c.slipping == 61);
  CHECK(c.exact == 61);
  CHECK(c.held == 39);
  CHECK(c.creep == 0.0);
  CHECK(c.min_normal == Approx(1.0));
  CHECK(c.max_normal == Approx(1.0));
  CHECK(c.mean_ratio == Approx(1.0).epsilon(1e-12));
  CHECK(c.median_ratio == Approx(1.0).epsilon(1e-12));
  // Coulomb's law on those normal impulses is the clamp law itself.
  const SlidePath own = coulomb_path(k, s, s.mu, kSixtieth);
  for (std::size_t n = 0; n < own.s.size(); ++n) CHECK(own.s[n] == Approx(law.s[n]).margin(1e-12));
}

TEST_CASE("a slide whose friction is 2 % off fails, strictly and by its median", "[impulses]") {
  const SlideSetup s = slide_stop_setup();
  SlideSetup off = s;
  off.mu *= 1.02;
  const std::vector<SlideImpulse> k = slide_impulses(
      level_states(slide_path(off, FrictionModel::cone, kSixtieth, 100)), s, kSixtieth);
  const CoulombCertificate strict = coulomb_certificate(k, s.mu, s.g, kSixtieth, 0.0);
  CHECK_FALSE(strict.holds);
  CHECK(strict.first_bad == 1);
  CHECK(strict.worst_over == Approx(0.02).epsilon(1e-9));
  const CoulombCertificate median = coulomb_certificate(k, s.mu, s.g, kSixtieth, 1e-3);
  CHECK_FALSE(median.holds);
  CHECK(median.median_ratio == Approx(1.02).epsilon(1e-9));
}

TEST_CASE("an iterative solver's stray steps are reported; its median step is judged",
          "[impulses]") {
  const SlideSetup s = slide_stop_setup();
  std::vector<SlideImpulse> k = slide_impulses(
      level_states(slide_path(s, FrictionModel::cone, kSixtieth, 100)), s, kSixtieth);
  // Three slipping steps stray: one 15 % over (stale friction), two 5 % short (a rocking box).
  k[14].along *= 1.15;
  k[20].along *= 0.95;
  k[40].along *= 0.95;
  const CoulombCertificate strict = coulomb_certificate(k, s.mu, s.g, kSixtieth, 0.0);
  CHECK_FALSE(strict.holds);
  CHECK(strict.first_bad == 15);
  const CoulombCertificate c = coulomb_certificate(k, s.mu, s.g, kSixtieth, 1e-3);
  CHECK(c.holds);
  CHECK(c.stale == 1);
  CHECK(c.worst_over_step == 15);
  CHECK(c.worst_over == Approx(0.15).epsilon(1e-9));
  CHECK(c.worst_short == Approx(0.05).epsilon(1e-9));
  CHECK(c.worst_short_step == 21);
  CHECK(c.exact == 58);
  CHECK(c.median_ratio == Approx(1.0).epsilon(1e-12));
  CHECK(c.mean_ratio == Approx(1.0 + (0.15 - 0.05 - 0.05) / 61).epsilon(1e-9));
}

TEST_CASE("a contact that pulls fails any solver", "[impulses]") {
  const SlideSetup s = slide_stop_setup();
  std::vector<SlideImpulse> k = slide_impulses(
      level_states(slide_path(s, FrictionModel::cone, kSixtieth, 100)), s, kSixtieth);
  k[69].normal = -0.01;
  const CoulombCertificate c = coulomb_certificate(k, s.mu, s.g, kSixtieth, 1e-3);
  CHECK_FALSE(c.holds);
  CHECK(c.pull_step == 70);
  CHECK(c.first_bad == 70);
}

TEST_CASE("a held box's slip after a sticking step is its creep", "[impulses]") {
  const SlideSetup s = slide_stop_setup();
  SlidePath law = slide_path(s, FrictionModel::cone, kSixtieth, 100);
  law.v[80] = 2e-4;  // after step 80 it still moves (the step's friction left it)
  const CoulombCertificate c = coulomb_certificate(slide_impulses(level_states(law), s, kSixtieth),
                                                   s.mu, s.g, kSixtieth, 1e-3);
  CHECK(c.creep == Approx(2e-4));
  CHECK(c.creep_step == 80);
}

TEST_CASE("a slide launched against its pull turns back, and friction opposes it both ways",
          "[impulses]") {
  // Launched up a slope at 1 m/s: the pull (3 m/s^2 down it) outgrips mu*g = 0.1*9.8, so it stops
  // and slides back; the step it turns, friction must oppose the slip friction has to cancel.
  SlideSetup s = slide_stop_setup();
  s.v0 = 1.0;
  s.mu = 0.1;
  s.pull = -3.0;
  const SlidePath law = slide_path(s, FrictionModel::cone, kSixtieth, 120);
  REQUIRE(law.v.back() < 0.0);  // it turned
  const CoulombCertificate c = coulomb_certificate(slide_impulses(level_states(law), s, kSixtieth),
                                                   s.mu, s.g, kSixtieth, 0.0);
  CHECK(c.holds);
  CHECK(c.slipping == 120);
  CHECK(c.exact == 120);
  CHECK(c.worst_short < 1e-9);
}
