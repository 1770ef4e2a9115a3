// Algorithm-specific settings by name (OptimizerOptions::settings, the command's --setting
// NAME=VALUE): the values arrive as text and each adapter reads what it knows, refusing the rest.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mbsopt {

using NamedSettings = std::vector<std::pair<std::string, std::string>>;

/// The whole of `value` as a number; throws std::invalid_argument naming the setting otherwise.
double settingNumber(const std::string& name, const std::string& value);

/// A comma-separated list of numbers ("1,2.5,1e3"); throws std::invalid_argument naming the setting.
std::vector<double> settingNumbers(const std::string& name, const std::string& value);

/// The error for a name an algorithm does not know, listing the ones it does.
[[noreturn]] void throwUnknownSetting(const std::string& algorithm, const std::string& name,
                                      const std::vector<std::string>& known);

}  // namespace mbsopt
