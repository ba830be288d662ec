#include "harness/core/build_id.hpp"

#include <Eigen/Core>
#include <cstdio>
#include <sstream>
#include <vector>

// Set for this file by harness/CMakeLists.txt; the fallbacks keep a hand-made build compiling.
#ifndef DROPCHECK_COMPILER
#define DROPCHECK_COMPILER "unknown compiler " __VERSION__
#endif
#ifndef DROPCHECK_BUILD_TYPE
#define DROPCHECK_BUILD_TYPE ""
#endif
#ifndef DROPCHECK_CXX_FLAGS
#define DROPCHECK_CXX_FLAGS ""
#endif
#ifndef DROPCHECK_SOURCE_TREE
#define DROPCHECK_SOURCE_TREE "."
#endif
#ifndef DROPCHECK_OURS_FLAGS
#define DROPCHECK_OURS_FLAGS "-ffp-contract=off"
#endif

namespace dropcheck {
namespace {

// Flags that change the results of IEEE arithmetic or of the math library (GCC and Clang names).
bool fp_relevant(const std::string& flag) {
  static const char* const kPrefixes[] = {"-ffast-math",
                                          "-ffp-",
                                          "-funsafe-math",
                                          "-fassociative-math",
                                          "-freciprocal-math",
                                          "-fno-signed-zeros",
                                          "-ffinite-math",
                                          "-frounding-math",
                                          "-fexcess-precision",
                                          "-ffloat-store",
                                          "-march=",
                                          "-mfma",
                                          "-mno-fma",
                                          "-mavx",
                                          "-msse",
                                          "-mfpmath",
                                          "-m32"};
  for (const char* p : kPrefixes)
    if (flag.rfind(p, 0) == 0) return true;
  return false;
}

const char* architecture() {
#if defined(__x86_64__)
  return "x86_64";
#elif defined(__aarch64__)
  return "aarch64";
#elif defined(__i386__)
  return "i386";
#else
  return "other-arch";
#endif
}

std::string libm_version() {
#if defined(__GLIBC__)
  return "glibc " + std::to_string(__GLIBC__) + "." + std::to_string(__GLIBC_MINOR__);
#else
  return "libm unknown";
#endif
}

// Single spaces between words, none at the ends.
std::string squeeze(const std::string& text) {
  std::istringstream in(text);
  std::string out, word;
  while (in >> word) out += (out.empty() ? "" : " ") + word;
  return out;
}

}  // namespace

std::string fp_flags(const std::string& flags) {
  std::istringstream in(flags);
  std::string opt = "-O0", rest, flag;
  while (in >> flag) {
    if (flag.rfind("-O", 0) == 0) {
      opt = flag == "-O" ? "-O1" : flag;
    } else if (fp_relevant(flag) && rest.find(flag) == std::string::npos) {
      rest += " " + flag;
    }
  }
  return opt + rest;
}

BuildId current_build() {
  BuildId id;
  id.build_type = DROPCHECK_BUILD_TYPE;
  id.flags = squeeze(DROPCHECK_CXX_FLAGS);
  const std::string eigen = "Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
                            std::to_string(EIGEN_MAJOR_VERSION) + "." +
                            std::to_string(EIGEN_MINOR_VERSION);
  id.key = std::string(architecture()) + ", " + DROPCHECK_COMPILER + ", " + eigen + ", " +
           libm_version() + ", " + fp_flags(id.flags + " " + DROPCHECK_OURS_FLAGS);
  return id;
}

std::string source_tree() {
  return DROPCHECK_SOURCE_TREE;
}

std::string source_commit() {
  return commit_stamp(source_tree());
}

std::string commit_stamp(const std::string& dir) {
  std::string quoted = "'";
  for (char c : dir) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  quoted += "'";
  const std::string command = "git -C " + quoted + " log -1 --format='%h %cs' 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return "unknown commit";
  char buf[128] = {};
  const bool got = std::fgets(buf, sizeof buf, pipe) != nullptr;
  pclose(pipe);
  std::string line = got ? buf : "";
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line.empty() ? "unknown commit" : line;
}

}  // namespace dropcheck
