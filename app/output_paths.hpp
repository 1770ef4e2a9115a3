// Output paths checked before any work: a run of minutes must not end in a raw filesystem error, and
// a wrong path must not replace an input. Each refusal is one line naming the option, the path and why.
#pragma once

#include <string>

namespace mbsopt {

/// A file an option writes (--json, simulate's --out): its directory exists and takes a new file, and
/// the path is neither a directory, a link, a device nor `input` (the scene file). std::invalid_argument
/// otherwise. An empty path is not asked for and passes.
void checkOutputFile(const std::string& option, const std::string& path, const std::string& input = "");

/// A directory an option fills (optimize's, compare's, precision's and benchmark's --out): it is created
/// now where missing, and takes a new file. std::invalid_argument otherwise. An empty path passes.
void checkOutputDirectory(const std::string& option, const std::string& path);

}  // namespace mbsopt
