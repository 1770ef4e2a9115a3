// The text of scene files and of their messages: numbers as written in a scene (with an optional
// `deg` suffix), numbers printed back, user text quoted safely into a one-line message, and
// "did you mean" suggestions.
#pragma once

#include <string>
#include <vector>

namespace mbsopt {

/// Parses a scene number: a decimal literal, optionally followed by `deg` (× π/180, exactly π/2
/// for 90 deg). Returns false and sets `why` when the text is not a finite number.
bool parseNumber(const std::string& text, double& value, std::string& why);
/// Whether a number's text carries the `deg` suffix (parseNumber then reads it in degrees).
bool writtenInDegrees(const std::string& text);

/// The shortest text that reads back as the same double ("0.1", "246000").
std::string formatNumber(double value);

/// `text` in single quotes for a one-line message: control characters escaped, at most 60 characters.
std::string quoted(const std::string& text);

/// " (did you mean 'x'?)" when one of `candidates` is a plausible typo of `word`, else "". The candidate
/// is quoted(): it may come from text not validated yet.
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace mbsopt
