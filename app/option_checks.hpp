// Checks of the command line's numbers whose refusal is one short line in the program's own words,
// "--every: must be a positive integer, got 0" (CLI11's own range checks print the whole range of a
// double), and exit status 1 with it (main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

/// A finite number > 0.
CLI::Validator positiveNumber();
/// A finite number ≥ 0.
CLI::Validator nonNegativeNumber();
/// A whole number ≥ 1.
CLI::Validator positiveInteger();
/// A finite number in [low, high].
CLI::Validator numberBetween(double low, double high);
/// A whole number in [low, high].
CLI::Validator integerBetween(long low, long high);

}  // namespace mbsopt
