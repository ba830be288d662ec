#include "args.hpp"

#include "harness/core/input_error.hpp"

namespace dropcheck {

std::string Args::value(const std::string& name, const std::string& fallback) const {
  auto it = options.find(name);
  return it == options.end() || it->second.empty() ? fallback : it->second.back();
}

const std::vector<std::string>& Args::values(const std::string& name) const {
  static const std::vector<std::string> none;
  auto it = options.find(name);
  return it == options.end() ? none : it->second;
}

Args parse_args(const std::vector<std::string>& argv, const std::set<std::string>& with_value,
                const std::set<std::string>& flag_names) {
  Args a;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& s = argv[i];
    if (s.rfind("--", 0) != 0 || s == "--") {
      a.positional.push_back(s);
    } else if (with_value.count(s)) {
      if (i + 1 >= argv.size()) throw InputError("", 0, s, "expects a value");
      a.options[s].push_back(argv[++i]);
    } else if (flag_names.count(s)) {
      a.flags.insert(s);
    } else {
      throw InputError("", 0, s, "unknown option");
    }
  }
  return a;
}

}  // namespace dropcheck
