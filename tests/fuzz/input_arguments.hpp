// The command-line arguments a fuzz input carries (docs/fuzzing.md): the words of its lines that
// start with "#!" (a YAML comment, so a scene stays a valid input), in order. One rule for the fuzz
// target and for the regression tests that replay its inputs through `mbsopt simulate`.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace mbsopt::fuzz {

inline std::vector<std::string> inputArguments(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("#!")) continue;
    std::istringstream split(line.substr(2));
    for (std::string word; split >> word;) words.push_back(word);
  }
  return words;
}

}  // namespace mbsopt::fuzz
