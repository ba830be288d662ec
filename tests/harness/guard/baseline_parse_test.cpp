// Tests harness/guard/baseline_parse.cpp on inputs fuzzing found
// (fuzz/regressions/baseline_parse/): the parser must refuse what the writer could not print back.
#include "harness/guard/baseline_parse.hpp"

#include <catch2/catch.hpp>

#include "../test_dirs.hpp"
#include "harness/core/input_error.hpp"
#include "harness/guard/baseline.hpp"
#include "harness/guard/baseline_io.hpp"

using namespace dropcheck;

TEST_CASE("a second bodies line after samples is refused, not read as more bodies", "[baseline]") {
  // Before the fix this parsed, and baseline_to_text read past the stored states (ASan:
  // heap-buffer-overflow in samples_text).
  const std::string found = dropcheck::testing::slurp(
      std::string(DROPCHECK_SOURCE_DIR) + "/fuzz/regressions/baseline_parse/samples_mismatch.txt");
  REQUIRE_FALSE(found.empty());
  REQUIRE_THROWS_WITH(parse_baseline(found, "x.txt"), Catch::Contains("a second 'bodies' line"));
  const std::string small =
      "scene s\nengine e\nhash 00\nbodies a\nsample 0 a 0 0 0 0 0 0\nbodies b\n";
  REQUIRE_THROWS_AS(parse_baseline(small, "y.txt"), InputError);
}
