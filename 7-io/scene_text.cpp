#include "mbsopt/io/scene_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string_view>

namespace mbsopt {

namespace {

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

}  // namespace

bool writtenInDegrees(const std::string& text) { return trimmed(text).ends_with("deg"); }

bool parseNumber(const std::string& text, double& value, std::string& why) {
  std::string_view digits = trimmed(text);
  const bool degrees = digits.ends_with("deg");
  if (degrees) digits = trimmed(digits.substr(0, digits.size() - 3));
  if (digits.starts_with('+') && !digits.starts_with("+-") && !digits.starts_with("++")) digits.remove_prefix(1);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || end != digits.data() + digits.size() || error == std::errc::invalid_argument) {
    why = "expected a number, got " + quoted(text);
    return false;
  }
  if (error == std::errc::result_out_of_range) {
    // from_chars leaves the value alone; strtod tells an underflow from an overflow.
    const bool underflow = std::abs(std::strtod(std::string(digits).c_str(), nullptr)) < 1.0;
    why = quoted(text) + (underflow ? " underflows to zero (write 0 if zero is meant)" : " overflows a double");
    return false;
  }
  if (!std::isfinite(value)) {
    why = quoted(text) + " is not a finite number";
    return false;
  }
  // (v / 180) π rather than v (π / 180): 90 deg is then exactly the double nearest π/2.
  if (degrees) value = value / 180.0 * std::numbers::pi;
  return true;
}

std::string formatNumber(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return {text.data(), result.ptr};
}

std::string quoted(const std::string& text) {
  constexpr std::size_t kLongest = 60;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kLongest; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    } else {
      out += text[i];
    }
  }
  if (text.size() > kLongest) out += "...";
  return out + "'";
}

std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
  std::string nearest;
  std::size_t best = std::max<std::size_t>(3, word.size() / 4 + 1);
  for (const std::string& candidate : candidates)
    if (const std::size_t d = editDistance(word, candidate); d < best) best = d, nearest = candidate;
  // quoted: a candidate may come from text not validated yet (an override's names are read from the
  // scene before its entries are checked), and a line break in it would split the message.
  return nearest.empty() ? "" : " (did you mean " + quoted(nearest) + "?)";
}

}  // namespace mbsopt
