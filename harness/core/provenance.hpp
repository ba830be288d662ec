// Provenance of a report: which commit, build and machine produced it, and when. Reproducible: the
// date is the commit date of HEAD (or SOURCE_DATE_EPOCH), never the wall clock, so that rerunning
// the report on the same commit and machine gives the same bytes.
#pragma once

#include <string>

namespace dropcheck {

struct Provenance {
  std::string date;        // ISO 8601: SOURCE_DATE_EPOCH when set, else HEAD's committer date
  std::string commit;      // abbreviated hash of HEAD, "-dirty" when tracked files differ from it
  std::string build;       // architecture, compiler and version, Eigen, libm, FP flags
  std::string build_type;  // CMAKE_BUILD_TYPE
  std::string flags;       // the build's C++ flags
  std::string cpu;         // "model name" of /proc/cpuinfo, with the number of logical CPUs
};

// The provenance of a report generated from the git checkout holding `dir` by this binary; when
// `dir` is in no checkout, from the source tree this binary was built from (build_id.hpp).
// Changes under `output_dir` (the report's own directory, committed in the repository) do not make
// the tree dirty: rerunning the report must not change its own provenance. Parts that cannot be
// found read "unknown".
Provenance current_provenance(const std::string& dir, const std::string& output_dir = "");

// "model name" of /proc/cpuinfo with the number of logical CPUs ("AMD EPYC 7B13, 2 logical CPUs");
// "" when it cannot be read.
std::string cpu_model();

// SOURCE_DATE_EPOCH (seconds since 1970, UTC) as ISO 8601 ("2026-11-21T18:24:33Z"); "" when the
// text is not a non-negative whole number.
std::string iso_date_from_epoch(const std::string& epoch);

}  // namespace dropcheck
