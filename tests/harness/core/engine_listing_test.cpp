// Tests harness/core/engine_listing.cpp against the one list of engines, adapters/engines.txt: the
// build's listing is that file's rows, in its order and with its figures, and the registry
// (adapters/registry.cpp) makes exactly the engines the listing says are compiled in.
#include "harness/core/engine_listing.hpp"

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"

namespace {

struct Row {
  std::string name, source, find, packages;
  double ns = 0.0;
  std::string contact_ns, slowdown;
};

std::vector<Row> engines_txt() {
  std::ifstream in(std::string(DROPCHECK_SOURCE_DIR) + "/adapters/engines.txt");
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Row r;
    fields >> r.name >> r.source >> r.find >> r.packages >> r.ns >> r.contact_ns >> r.slowdown;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("the engine listing is adapters/engines.txt, row for row", "[engine][listing]") {
  const std::vector<Row> rows = engines_txt();
  const auto& listing = dropcheck::engine_listings();
  REQUIRE(rows.size() == listing.size());
  REQUIRE(rows.size() >= 2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    INFO(rows[i].name);
    CHECK(listing[i].name == rows[i].name);
    CHECK(listing[i].nominal_ns_per_body_step == rows[i].ns);
    CHECK(listing[i].nominal_contact_ns_per_body_step ==
          (rows[i].contact_ns == "-" ? rows[i].ns : std::stod(rows[i].contact_ns)));
    CHECK(listing[i].slowdown_threshold ==
          (rows[i].slowdown == "-" ? 0.0 : std::stod(rows[i].slowdown)));
    CHECK(listing[i].packages == (rows[i].packages == "-" ? "" : rows[i].packages));
    const std::string option = rows[i].find == "none" ? "" : "DROPCHECK_WITH_";
    CHECK(listing[i].option.rfind(option, 0) == 0);
    CHECK(dropcheck::find_engine_listing(rows[i].name) == &listing[i]);
  }
  CHECK(dropcheck::find_engine_listing("exec:./my-engine") == nullptr);
}

TEST_CASE("the registry makes exactly the engines the listing says are compiled in",
          "[engine][listing]") {
  std::vector<std::string> compiled;
  for (const auto& l : dropcheck::engine_listings()) {
    INFO(l.name);
    if (l.compiled_in) compiled.push_back(l.name);
    const auto engine = dropcheck::make_engine(l.name);
    CHECK((engine != nullptr) == l.compiled_in);
    if (engine) CHECK(engine->info().name == l.name);
    CHECK(dropcheck::engine_unavailable_reason(l.name).empty() == l.compiled_in);
  }
  CHECK(dropcheck::available_engine_names() == compiled);
  CHECK_THAT(dropcheck::engine_unavailable_reason("nosuch"),
             Catch::Matchers::Contains("known: ours, ours-f64, bullet"));
}
