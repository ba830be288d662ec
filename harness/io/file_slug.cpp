#include "harness/io/file_slug.hpp"

#include "harness/core/trajectory_hash.hpp"

namespace dropcheck {

std::string file_slug(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '_' || c == '.';
    out += keep ? c : '_';
  }
  if (out.empty() || out[0] == '.') out.insert(out.begin(), '_');
  if (out.size() > kMaxSlugBytes) out = out.substr(0, kMaxSlugBytes - 17) + "~" + fnv1a_hex(name);
  return out;
}

}  // namespace dropcheck
