// Output files that never exist half written: written under a temporary name next to the target,
// then renamed; the temporary file is removed on any failure.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace mbsopt {

/// Throws std::runtime_error naming the file and the system's reason when it cannot be written.
void writeAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace mbsopt
