// A registry's entries (integrators, gradient methods, optimizers, formulations: each a list of
// records with a name and a one-sentence description) as a flag's --help text, so that it is not
// written a second time beside the registry (each registry gives its names for CLI::IsMember).
#pragma once

#include <string>

namespace mbsopt {

/// "name: description; name: description" for --help.
template <class Registry>
std::string describedChoices(const Registry& entries) {
  std::string text;
  for (const auto& entry : entries) text += (text.empty() ? "" : "; ") + entry.name + ": " + entry.description;
  return text;
}

}  // namespace mbsopt
