// A small command-line option parser: --name VALUE, --name=VALUE, short -x VALUE, flags.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace gdr::cli {

struct OptionSpec {
  std::string name;        // long name without dashes, e.g. "min-angle"
  char short_name = 0;     // e.g. 'o', or 0
  bool takes_value = false;
  std::function<void(const std::string& value)> apply;  // value is "" for flags
};

// Applies every option in order and returns the positional arguments.
// Throws UsageError(command, ...) for unknown options and missing values.
std::vector<std::string> parse_options(const std::string& command,
                                       const std::vector<std::string>& args,
                                       const std::vector<OptionSpec>& specs);

// Strict number parsing for option values; throws UsageError naming the option.
double parse_number(const std::string& command, const std::string& option,
                    const std::string& value);
long long parse_integer(const std::string& command, const std::string& option,
                        const std::string& value);

}  // namespace gdr::cli
