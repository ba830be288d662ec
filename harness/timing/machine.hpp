// The machine a report's timings were measured on, as /proc, /sys and uname describe it: what the
// slowdown alert compares before it judges a figure against another record. Absolute times and
// even times over the calibration loop do not carry from one machine to another (two machines of
// one kind moved a median 13 % and up to 82 % apart: engines meet different memory and branch
// behaviour), so a record from another machine is shown, never judged.
#pragma once

#include <string>
#include <vector>

namespace dropcheck {

struct Machine {
  std::string cpu;     // "model name" of /proc/cpuinfo
  std::string cpu_id;  // "family 6, model 207, stepping 2"
  std::string caches;  // cpu0's caches: "L1d 48K, L1i 32K, L2 2048K, L3 307200K"
  int logical_cpus = 0;
  std::string kernel;  // uname's release
  // FNV-1a of /etc/machine-id and the host name, in hex: two installations on identical hardware
  // differ here (and two containers of one image, by their host names); neither is written out.
  std::string installation;
};

// This machine; a field it cannot read stays empty (0 CPUs).
Machine this_machine();

// The names of the fields in which `a` and `b` differ ("cpu", "caches", "installation", ...), in
// the order of Machine; every field when either says nothing at all (a record from before
// dropcheck wrote the machine). Empty: the same machine.
std::vector<std::string> machine_differences(const Machine& a, const Machine& b);

// "Intel(R) Xeon(R) Processor (family 6, model 207, stepping 2; L1d 48K, L1i 32K, L2 2048K, L3
// 307200K), 2 logical CPUs, Linux 6.1.0, installation 3f2a9c0e1b7d4a55"; "not recorded" when
// empty.
std::string describe(const Machine& m);

}  // namespace dropcheck
