// What built this binary, as far as it can change the bits of a trajectory: the key of the
// bit-identical regression tier (harness/guard/regression.hpp) and the header line of every
// baseline.
#pragma once

#include <string>

namespace dropcheck {

// The identity of this build as the regression guard sees it.
struct BuildId {
  // Everything that can change ours' floating-point results: architecture, compiler and version,
  // Eigen and libm versions, optimisation level and FP-relevant flags. Equal keys: equal bits.
  std::string key;
  std::string build_type;  // CMAKE_BUILD_TYPE ("Debug", "RelWithDebInfo", ...), "" when unset
  std::string flags;       // every C++ flag of the build (CMAKE_CXX_FLAGS + the build type's)
};

// The build this binary came from (compile definitions set in harness/CMakeLists.txt).
BuildId current_build();

// The FP-relevant part of a flag string, normalised: the last -O level ("-O0" when none), then
// -ffast-math, -ffp-contract=..., -march=..., -mfma, ... in order. Sanitizers, -g, -W... are left
// out: they do not change results. (Measured, GCC 12.2: -O0 and -O2 with ASan/UBSan gave identical
// hashes on every shipped scene; the level stays in the key because it may change bits elsewhere.)
std::string fp_flags(const std::string& flags);

// The source tree this binary was built from (CMake's source directory at configure time).
std::string source_tree();

// commit_stamp of the source tree this binary was built from.
std::string source_commit();

// "a139440 2026-11-21": the abbreviated hash and commit date of HEAD of the git checkout holding
// `dir`, or "unknown commit" when git or the checkout is unavailable.
std::string commit_stamp(const std::string& dir);

}  // namespace dropcheck
