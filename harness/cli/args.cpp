#include "args.hpp"

#include <CLI/CLI.hpp>

#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

std::string count_words(const CommandSpec& spec) {
  if (spec.max_positional < 0)
    return (spec.min_positional ? "one or more " : "any number of ") + spec.positional_name + "s";
  if (spec.min_positional == spec.max_positional)
    return (spec.min_positional == 1 ? "exactly one " : "exactly two ") + spec.positional_name;
  return "at most " + std::to_string(spec.max_positional) + " " + spec.positional_name;
}

// The parser of `spec`; values are collected per occurrence. Positionals are not declared to CLI11:
// they come back in remaining() with unknown options and a bare "--", sorted out by parse_args.
std::unique_ptr<CLI::App> make_app(const CommandSpec& spec,
                                   std::map<std::string, std::vector<std::string>>& values) {
  auto app = std::make_unique<CLI::App>(spec.summary, "dropcheck " + spec.name);
  app->allow_extras();  // reported below with our own sentences
  app->get_formatter()->column_width(24);
  for (const OptionSpec& o : spec.options) {
    if (o.value_name.empty()) {
      app->add_flag(o.name, o.help);
      continue;
    }
    CLI::Option* opt = app->add_option(o.name, values[o.name], o.help);
    opt->type_name(o.value_name)->allow_extra_args(false)->expected(1);
    opt->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  }
  if (!spec.positional_name.empty())
    app->footer(spec.positional_name + ": " + spec.positional_help + " (" + count_words(spec) +
                ")");
  return app;
}

void check_values(const CommandSpec& spec, const CLI::App& app, Args& args,
                  const std::map<std::string, std::vector<std::string>>& values) {
  for (const OptionSpec& o : spec.options) {
    const std::size_t n = app.get_option(o.name)->count();
    if (n == 0) continue;
    if (o.value_name.empty()) {
      args.flags.insert(o.name);
      continue;
    }
    const std::vector<std::string>& v = values.at(o.name);
    if (!o.repeatable && v.size() > 1)
      throw InputError("", 0, o.name, "given " + std::to_string(v.size()) + " times; give it once");
    for (const std::string& s : v)
      if (s.empty())
        throw InputError("", 0, o.name, "expects " + o.value_name + ", got an empty string");
    args.options[o.name] = v;
  }
}

}  // namespace

std::string Args::value(const std::string& name, const std::string& fallback) const {
  auto it = options.find(name);
  return it == options.end() || it->second.empty() ? fallback : it->second.back();
}

const std::vector<std::string>& Args::values(const std::string& name) const {
  static const std::vector<std::string> none;
  auto it = options.find(name);
  return it == options.end() ? none : it->second;
}

Args parse_args(const CommandSpec& spec, const std::vector<std::string>& argv) {
  Args args;
  std::map<std::string, std::vector<std::string>> values;
  const std::unique_ptr<CLI::App> app = make_app(spec, values);
  const std::string hint = " (see dropcheck " + spec.name + " --help)";
  try {
    app->parse(std::vector<std::string>(argv.rbegin(), argv.rend()));
  } catch (const CLI::CallForHelp&) {
    throw HelpRequested{app->help()};
  } catch (const CLI::ArgumentMismatch& e) {  // "--csv: 1 required OUT missing"
    const std::string what = e.what();
    throw InputError("", 0, what.substr(0, what.find(':')), "expects a value" + hint);
  } catch (const CLI::ParseError& e) {
    throw InputError("", 0, "", std::string(e.what()) + hint);
  }
  bool options_ended = false;
  for (const std::string& extra : app->remaining()) {
    if (!options_ended && extra == "--") {
      options_ended = true;
    } else if (!options_ended && extra.size() > 1 && extra[0] == '-') {
      throw InputError("", 0, extra, "unknown option" + hint);
    } else {
      args.positional.push_back(extra);
    }
  }
  const int n = static_cast<int>(args.positional.size());
  if (spec.positional_name.empty() && n > 0)
    throw InputError("", 0, "",
                     "unexpected argument '" + args.positional[0] + "': " + spec.name +
                         " takes no arguments" + hint);
  if (n < spec.min_positional || (spec.max_positional >= 0 && n > spec.max_positional))
    throw InputError("", 0, spec.name,
                     "expects " + count_words(spec) + ", got " + std::to_string(n) + hint);
  check_values(spec, *app, args, values);
  return args;
}

std::string help_text(const CommandSpec& spec) {
  std::map<std::string, std::vector<std::string>> values;
  return make_app(spec, values)->help();
}

}  // namespace dropcheck
