#include "mbsopt/optimizers/optimizer_settings.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbsopt {

double settingNumber(const std::string& name, const std::string& value) {
  std::size_t used = 0;
  double number = 0.0;
  try {
    number = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(number))
    throw std::invalid_argument("setting " + name + ": '" + value + "' is not a finite number");
  return number;
}

std::vector<double> settingNumbers(const std::string& name, const std::string& value) {
  std::vector<double> numbers;
  std::istringstream list(value);
  for (std::string item; std::getline(list, item, ',');) numbers.push_back(settingNumber(name, item));
  return numbers;
}

void throwUnknownSetting(const std::string& algorithm, const std::string& name, const std::vector<std::string>& known) {
  std::string list;
  for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
  throw std::invalid_argument(algorithm + " has no setting '" + name + "'" +
                              (known.empty() ? std::string(" (it takes none)") : " (it takes: " + list + ")"));
}

}  // namespace mbsopt
