// A registry's entries (integrators, gradient methods, optimizers, formulations: each a list of
// records with a name and a one-sentence description) as a flag's --help text and its accepted
// names, so that neither is written a second time beside the registry.
#pragma once

#include <string>
#include <vector>

namespace mbsopt {

/// "name: description; name: description" for --help.
template <class Registry>
std::string describedChoices(const Registry& entries) {
  std::string text;
  for (const auto& entry : entries) text += (text.empty() ? "" : "; ") + entry.name + ": " + entry.description;
  return text;
}

/// The names, for CLI::IsMember.
template <class Registry>
std::vector<std::string> choiceNames(const Registry& entries) {
  std::vector<std::string> names;
  for (const auto& entry : entries) names.push_back(entry.name);
  return names;
}

}  // namespace mbsopt
