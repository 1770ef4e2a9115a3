// The command line mbsopt was started with, for the outputs that say how they were made.
#pragma once

#include <string>

namespace mbsopt {

/// Records argv once, at the start of main.
void recordCommandLine(int argc, const char* const* argv);
/// The recorded command line, one string, each argument a shell would split or expand in single
/// quotes; empty when none was recorded (a library caller).
const std::string& commandLine();

}  // namespace mbsopt
