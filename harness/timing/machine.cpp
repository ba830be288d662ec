#include "harness/timing/machine.hpp"

#include <fmt/format.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <fstream>
#include <string_view>

#include "harness/core/number_format.hpp"
#include "harness/core/trajectory_hash.hpp"

namespace dropcheck {
namespace {

// The first line of a small text file, "" when it cannot be read.
std::string first_line(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return {};
  return line.substr(0, 256);
}

// The value of the first "key : value" line of /proc/cpuinfo whose key is `key`.
std::string cpuinfo(std::string_view key) {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  for (int n = 0; n < 200 && std::getline(in, line); ++n) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string k = line.substr(0, colon);
    while (!k.empty() && (k.back() == ' ' || k.back() == '\t')) k.pop_back();
    if (k != key) continue;
    const std::size_t start = line.find_first_not_of(' ', colon + 1);
    return start == std::string::npos ? std::string() : line.substr(start, 256);
  }
  return {};
}

// cpu0's caches from /sys: "L1d 48K, L1i 32K, L2 2048K, L3 307200K".
std::string caches() {
  std::string out;
  for (int i = 0; i < 8; ++i) {
    // fmt, not operator+: GCC 12 at -O2 reports a false array-bounds write in string concatenation.
    const std::string dir = fmt::format("/sys/devices/system/cpu/cpu0/cache/index{}/", i);
    const std::string level = first_line(fmt::format("{}level", dir));
    const std::string size = first_line(fmt::format("{}size", dir));
    if (level.empty() || size.empty()) continue;
    const std::string type = first_line(fmt::format("{}type", dir));
    const char* suffix = type == "Data" ? "d" : type == "Instruction" ? "i" : "";
    out += fmt::format("{}L{}{} {}", out.empty() ? "" : ", ", level, suffix, size);
  }
  return out;
}

// /etc/machine-id and the host name: containers made from one image share the first, and get a
// host name of their own each.
std::string installation() {
  std::array<char, 256> host{};
  if (gethostname(host.data(), host.size() - 1) != 0) host[0] = '\0';
  const std::string id = first_line("/etc/machine-id") + "/" + host.data();
  return id == "/" ? std::string() : printf_string("%016llx", (unsigned long long)fnv1a(id));
}

// At most the 256 characters a timings record's reader takes of a text.
std::string bounded(std::string text) {
  if (text.size() > 256) text.resize(256);
  return text;
}

}  // namespace

Machine this_machine() {
  Machine m;
  m.cpu = cpuinfo("model name");
  const std::string family = cpuinfo("cpu family"), model = cpuinfo("model"),
                    stepping = cpuinfo("stepping");
  if (!family.empty())
    m.cpu_id = bounded("family " + family + ", model " + model + ", stepping " + stepping);
  m.caches = bounded(caches());
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  m.logical_cpus = cpus > 0 ? static_cast<int>(cpus) : 0;
  utsname u{};
  if (uname(&u) == 0) m.kernel = u.release;
  m.installation = installation();
  return m;
}

std::vector<std::string> machine_differences(const Machine& a, const Machine& b) {
  const bool unknown = a.installation.empty() || b.installation.empty();
  std::vector<std::string> out;
  const auto differ = [&](const char* name, bool same) {
    if (unknown || !same) out.emplace_back(name);
  };
  differ("cpu", a.cpu == b.cpu);
  differ("cpu_id", a.cpu_id == b.cpu_id);
  differ("caches", a.caches == b.caches);
  differ("logical_cpus", a.logical_cpus == b.logical_cpus);
  differ("kernel", a.kernel == b.kernel);
  differ("installation", a.installation == b.installation);
  return out;
}

std::string describe(const Machine& m) {
  if (m.installation.empty() && m.cpu.empty()) return "not recorded";
  return (m.cpu.empty() ? "unknown CPU" : m.cpu) + " (" + m.cpu_id + "; " + m.caches + "), " +
         std::to_string(m.logical_cpus) + " logical CPUs, Linux " + m.kernel + ", installation " +
         m.installation;
}

}  // namespace dropcheck
