#include "mbsopt/io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mbsopt {

void writeAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string partial = path + ".partial";
  {
    std::ofstream out(partial);
    if (!out) throw std::runtime_error("cannot write '" + partial + "': " + std::strerror(errno));
    try {
      write(out);
    } catch (...) {
      std::remove(partial.c_str());
      throw;
    }
    if (!out.flush()) {
      std::remove(partial.c_str());
      throw std::runtime_error("writing '" + path + "' failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot replace '" + path + "': " + error.message());
  }
}

}  // namespace mbsopt
