#include "args.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "cli.h"

namespace gdr::cli {

namespace {

const OptionSpec* find_long(const std::vector<OptionSpec>& specs, const std::string& name) {
  for (const auto& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

const OptionSpec* find_short(const std::vector<OptionSpec>& specs, char c) {
  for (const auto& s : specs)
    if (s.short_name != 0 && s.short_name == c) return &s;
  return nullptr;
}

}  // namespace

std::vector<std::string> parse_options(const std::string& command,
                                       const std::vector<std::string>& args,
                                       const std::vector<OptionSpec>& specs) {
  std::vector<std::string> positional;
  bool options_done = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (options_done || a.size() < 2 || a[0] != '-') {
      positional.push_back(a);
      continue;
    }
    if (a == "--") {
      options_done = true;
      continue;
    }
    const OptionSpec* spec = nullptr;
    std::string shown, value;
    bool has_inline_value = false;
    if (a[1] == '-') {
      std::string name = a.substr(2);
      const auto eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        has_inline_value = true;
      }
      spec = find_long(specs, name);
      shown = "--" + name;
    } else if (a.size() == 2) {
      spec = find_short(specs, a[1]);
      shown = a;
    } else if (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.') {
      positional.push_back(a);  // a negative number is a positional argument
      continue;
    }
    if (!spec) throw UsageError(command, "unknown option '" + a + "'");
    if (!spec->takes_value) {
      if (has_inline_value) throw UsageError(command, "option '" + shown + "' takes no value");
      spec->apply("");
      continue;
    }
    if (!has_inline_value) {
      if (i + 1 >= args.size()) throw UsageError(command, "option '" + shown + "' needs a value");
      value = args[++i];
    }
    spec->apply(value);
  }
  return positional;
}

double parse_number(const std::string& command, const std::string& option,
                    const std::string& value) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError(command, "option '--" + option + "' expects a number, got '" + value + "'");
  return v;
}

long long parse_integer(const std::string& command, const std::string& option,
                        const std::string& value) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno == ERANGE)
    throw UsageError(command, "option '--" + option + "' expects an integer, got '" + value + "'");
  return v;
}

}  // namespace gdr::cli
