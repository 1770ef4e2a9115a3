// Where a record comes from: the version of mbsopt that made it and the command line the process was
// started with.
#pragma once

#include <string>

namespace mbsopt {

/// The library's version, "MAJOR.MINOR.PATCH" (the project's version in CMakeLists.txt).
const char* version();

/// Records argv once, at the start of main.
void recordCommandLine(int argc, const char* const* argv);
/// The recorded command line, one string, each argument a shell would split or expand in single
/// quotes; empty when none was recorded (a library caller).
const std::string& commandLine();

}  // namespace mbsopt
