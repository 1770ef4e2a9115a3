#include "app/output_paths.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace mbsopt {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& path, const std::string& why) {
  throw std::invalid_argument(option + " " + path + ": " + why);
}

/// Whether a new file can be written in `directory`: a probe file created and removed.
bool takesNewFiles(const fs::path& directory) {
  const fs::path probe = directory / (".mbsopt-write-probe-" + std::to_string(::getpid()));
  const bool written = static_cast<bool>(std::ofstream(probe));
  std::error_code ignored;
  fs::remove(probe, ignored);
  return written;
}

}  // namespace

void checkOutputFile(const std::string& option, const std::string& path, const std::string& input) {
  if (path.empty()) return;
  const fs::path file(path);
  const fs::path directory = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code error;
  if (!fs::is_directory(directory, error)) refuse(option, path, "its directory does not exist");
  const fs::file_status status = fs::symlink_status(file, error);
  if (fs::exists(status) && !fs::is_regular_file(status))
    refuse(option, path, "exists and is not a regular file (a directory, a link or a device); give a file name");
  if (!input.empty() && fs::exists(status) && fs::exists(input) && fs::equivalent(file, input, error))
    refuse(option, path, "is the scene file itself");
  if (!takesNewFiles(directory)) refuse(option, path, "its directory cannot be written");
}

void checkOutputDirectory(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  std::error_code error;
  fs::create_directories(path, error);
  if (error) refuse(option, path, "cannot be created (" + error.message() + ")");
  if (!fs::is_directory(path, error)) refuse(option, path, "exists and is not a directory");
  if (!takesNewFiles(path)) refuse(option, path, "cannot be written");
}

}  // namespace mbsopt
