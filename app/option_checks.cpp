#include "app/option_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace mbsopt {

namespace {

/// The text as a finite number, if it is one entirely.
bool finiteNumber(const std::string& text, double& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && errno == 0 && std::isfinite(value);
}

bool wholeNumber(const std::string& text, long& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtol(text.c_str(), &end, 10);
  return !text.empty() && end == text.c_str() + text.size() && errno == 0;
}

CLI::Validator numberCheck(std::string what, bool (*holds)(double, double, double), double low, double high) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0.0;
        if (finiteNumber(text, value) && holds(value, low, high)) return "";
        return "must be " + what + ", got " + text;
      },
      what);
}

CLI::Validator integerCheck(std::string what, long low, long high) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        long value = 0;
        if (wholeNumber(text, value) && value >= low && value <= high) return "";
        return "must be " + what + ", got " + text;
      },
      what);
}

}  // namespace

CLI::Validator positiveNumber() {
  return numberCheck("a positive number", [](double x, double, double) { return x > 0.0; }, 0.0, 0.0);
}

CLI::Validator nonNegativeNumber() {
  return numberCheck("a number of at least 0", [](double x, double, double) { return x >= 0.0; }, 0.0, 0.0);
}

CLI::Validator numberBetween(double low, double high) {
  char range[80];
  std::snprintf(range, sizeof range, "a number from %g to %g", low, high);
  return numberCheck(range, [](double x, double l, double h) { return x >= l && x <= h; }, low, high);
}

CLI::Validator integerBetween(long low, long high) {
  return integerCheck("a whole number from " + std::to_string(low) + " to " + std::to_string(high), low, high);
}

CLI::Validator positiveInteger() { return integerCheck("a positive integer", 1, std::numeric_limits<long>::max()); }

}  // namespace mbsopt
