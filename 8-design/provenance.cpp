#include "mbsopt/design/provenance.hpp"

#include <string_view>

namespace mbsopt {

namespace {

std::string& recorded() {
  static std::string line;
  return line;
}

/// The argument as a POSIX shell reads it back: as it is when it holds only safe characters, in
/// single quotes otherwise (a quote inside as '\'').
std::string quoted(std::string_view argument) {
  constexpr std::string_view kSafe =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789@%+=:,./_-";
  if (!argument.empty() && argument.find_first_not_of(kSafe) == std::string_view::npos) return std::string(argument);
  std::string out = "'";
  for (const char c : argument) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

const char* version() { return MBSOPT_VERSION; }

void recordCommandLine(int argc, const char* const* argv) {
  std::string& line = recorded();
  line.clear();
  for (int i = 0; i < argc; ++i) {
    if (i > 0) line += ' ';
    line += quoted(argv[i]);
  }
}

const std::string& commandLine() { return recorded(); }

}  // namespace mbsopt
