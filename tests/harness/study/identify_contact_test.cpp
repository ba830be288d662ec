// Tests harness/study/identify_contact.cpp: identify names the bounce law and the turned-box
// contact law a run follows, among the ideal law and every member this build's adapters declare
// (the printed lines are tested in tests/harness/cli/run_test.cpp).
#include "harness/study/identify_contact.hpp"

#include <algorithm>
#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;
using Catch::Contains;

TEST_CASE("identify on a bounce: the declared member follows, the others depart",
          "[identify][contact]") {
  const Scene scene = testing::shipped("bounce_e05");
  for (const char* name : {"ours-f64", "ode"}) {
    const std::unique_ptr<Engine> engine = make_engine(name);
    const ContactLawIdentity id = identify_bounce_law(scene, *engine, scene.timestep.seconds);
    INFO(name);
    CHECK(id.ok());
    REQUIRE(id.fits.size() >= 3);  // its own, the ideal law, and at least one other adapter's
    CHECK(id.fits.front().member == describe(engine->info().bounce_law));
    CHECK(std::find(id.fits.front().declared_by.begin(), id.fits.front().declared_by.end(), name) !=
          id.fits.front().declared_by.end());
    for (std::size_t i = 1; i < id.fits.size(); ++i) {
      CHECK_FALSE(id.fits[i].follows);
      CHECK_THAT(id.fits[i].detail, Contains("departs at step"));
    }
  }
}

TEST_CASE("identify on a tumbling landing: ours follows its mean-corner law; ODE declares none",
          "[identify][contact]") {
  const Scene scene = testing::shipped("tumble_drop");
  const std::unique_ptr<Engine> ours = make_engine("ours");
  const ContactLawIdentity o = identify_turned_contact(scene, *ours, scene.timestep.seconds);
  CHECK(o.ok());
  CHECK_FALSE(o.undeclared);
  REQUIRE(o.fits.size() == 1);
  CHECK(o.fits[0].follows);
  const std::unique_ptr<Engine> ode = make_engine("ode");
  const ContactLawIdentity d = identify_turned_contact(scene, *ode, scene.timestep.seconds);
  CHECK(d.ok());  // nothing declared, nothing to match
  CHECK(d.undeclared);
  REQUIRE(d.fits.size() == 1);
  CHECK_FALSE(d.fits[0].judged);  // ODE damps after the position update: the law's free step is
                                  // not its own
}

TEST_CASE("identify on a slide names the contact solver: its iterations, its re-solve, exactness",
          "[identify][contact]") {
  const Scene scene = testing::shipped("slide_stop");
  const double h = scene.timestep.seconds;
  const auto fit_of = [](const ContactLawIdentity& id, const std::string& part) {
    const auto it = std::find_if(id.fits.begin(), id.fits.end(), [&](const ContactMemberFit& f) {
      return f.member.find(part) != std::string::npos;
    });
    REQUIRE(it != id.fits.end());
    return *it;
  };
  if (const std::unique_ptr<Engine> box2d = make_engine("box2d")) {
    // Box2D stops at step 65 with its 8 velocity iterations, at 62 with 32: its run follows its
    // own count and no neighbour's.
    const ContactLawIdentity id = identify_contact_solver(scene, *box2d, h);
    CHECK(id.ok());
    CHECK_THAT(id.fits.front().member, Contains("8 velocity"));
    CHECK(fit_of(id, "(2 velocity").judged);
    CHECK_FALSE(fit_of(id, "(2 velocity").follows);
    CHECK_FALSE(fit_of(id, "(32 velocity").follows);
    CHECK_FALSE(fit_of(id, "solved exactly").follows);
  }
  if (const std::unique_ptr<Engine> ode = make_engine("ode")) {
    // ODE solves each step exactly: no replayed solver follows it.
    const ContactLawIdentity id = identify_contact_solver(scene, *ode, h);
    CHECK(id.ok());
    CHECK(id.fits.front().member == "solved exactly every step");
    for (std::size_t i = 1; i < id.fits.size(); ++i) CHECK_FALSE(id.fits[i].follows);
  }
  if (const std::unique_ptr<Engine> mujoco = make_engine("mujoco")) {
    const ContactLawIdentity id = identify_contact_solver(scene, *mujoco, h);
    CHECK(id.ok());
    CHECK_THAT(id.fits.front().member, Contains("MuJoCo"));
    CHECK_FALSE(fit_of(id, "Box2D 2.4 sequential impulses (8").follows);
  }
}
