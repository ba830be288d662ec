// Tests harness/core/build_id.cpp: the build key keeps exactly the flags that can change FP
// results.
#include "harness/core/build_id.hpp"

#include <catch2/catch.hpp>

using namespace dropcheck;

TEST_CASE("The FP key keeps the optimisation level and FP flags and drops the rest", "[baseline]") {
  CHECK(fp_flags("") == "-O0");
  CHECK(fp_flags("-g") == "-O0");
  CHECK(fp_flags("-Werror -fsanitize=address,undefined -fno-omit-frame-pointer -O2 -g -DNDEBUG "
                 "-ffp-contract=off") == "-O2 -ffp-contract=off");
  CHECK(fp_flags("-O3 -DNDEBUG -O1 -march=native -ffast-math -ffast-math") ==
        "-O1 -march=native -ffast-math");
  CHECK(fp_flags("-O -mfma") == "-O1 -mfma");
}

TEST_CASE("This build's key names the compiler, libraries and ours' -ffp-contract=off",
          "[baseline]") {
  const BuildId id = current_build();
  CHECK_THAT(id.key, Catch::Contains("Eigen 3.") && Catch::Contains("-ffp-contract=off"));
  CHECK_THAT(id.key, Catch::StartsWith("x86_64, GNU ") || Catch::StartsWith("aarch64, ") ||
                         Catch::Contains("Clang"));
  CHECK(commit_stamp("/") == "unknown commit");
}
