// Tests harness/core/provenance.cpp: a report names the commit that made it, also when written
// from outside any checkout, and SOURCE_DATE_EPOCH reads as an ISO date.
#include "harness/core/provenance.hpp"

#include <catch2/catch.hpp>
#include <filesystem>

#include "harness/core/build_id.hpp"

using namespace dropcheck;

TEST_CASE("provenance names the commit, from outside a checkout too", "[provenance]") {
  const Provenance here = current_provenance(DROPCHECK_SOURCE_DIR);
  INFO(here.commit);
  CHECK(here.commit != "unknown");
  CHECK(here.commit.find_first_not_of("0123456789abcdef-dirty") == std::string::npos);
  CHECK(here.date != "unknown");
  // A fresh folder outside any checkout: the source tree this binary was built from stands in.
  const std::filesystem::path outside =
      std::filesystem::temp_directory_path() / "dropcheck-provenance-outside";
  std::filesystem::create_directories(outside);
  const Provenance elsewhere = current_provenance(outside.string());
  std::filesystem::remove(outside);
  CHECK(elsewhere.commit == here.commit);
  CHECK(elsewhere.date == here.date);
  CHECK(source_tree() == DROPCHECK_SOURCE_DIR);
}

TEST_CASE("SOURCE_DATE_EPOCH reads as an ISO date, anything else as nothing", "[provenance]") {
  CHECK(iso_date_from_epoch("0") == "1970-01-01T00:00:00Z");
  CHECK(iso_date_from_epoch("1795000000") == "2026-11-18T11:06:40Z");
  CHECK(iso_date_from_epoch("").empty());
  CHECK(iso_date_from_epoch("-1").empty());
  CHECK(iso_date_from_epoch("12a").empty());
}
