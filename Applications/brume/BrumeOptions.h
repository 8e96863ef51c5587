// SPDX-License-Identifier: BSD-3-Clause
// The values of `brume`'s options: strict parsers, and CLI11 validators that
// use them and say what was expected. Integers are decimal and whole
// ("12abc", "0x10" and "1e3" are refused); a validated value is rewritten in
// a canonical form, so CLI11's own conversion gives exactly the parsed value.
#ifndef BrumeOptions_h
#define BrumeOptions_h

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace BrumeOptions
{
/// A decimal integer in [minimum, maximum], the whole text.
bool ParseInteger(const std::string& text, long long minimum, long long maximum, long long& value);

/// A number (strtod's syntax) in [minimum, maximum], the whole text.
bool ParseNumber(const std::string& text, double minimum, double maximum, double& value);

/// WIDTHxHEIGHT, each an integer in [1, maximum].
bool ParseSize(const std::string& text, int maximum, int& width, int& height);

/// MIN:MAX, integers with minimum <= MIN <= MAX <= maximum.
bool ParseRange(
  const std::string& text, long long minimum, long long maximum, long long& low, long long& high);

/// Why `keys` cannot be pressed at the start of `brume view` (empty when
/// they can): p, d and m, and s only in the timer-driven window.
std::string CheckKeys(const std::string& keys, bool exitAfter);

// Validators. `expected` completes "expected ..., not 'TEXT'", the message
// of a refused value (CLI11 puts the option's name before it).
CLI::Validator Integer(long long minimum, long long maximum, const std::string& expected);
CLI::Validator Number(double minimum, double maximum, const std::string& expected);
CLI::Validator Size(int maximum);
CLI::Validator Range(long long minimum, long long maximum, const std::string& expected);
/// One of `choices`, spelled exactly.
CLI::Validator OneOf(const std::vector<std::string>& choices);
/// Not empty; `expected` as above ("a file name").
CLI::Validator NotEmpty(const std::string& expected);
/// A file name ending in one of `suffixes`.
CLI::Validator Suffix(const std::vector<std::string>& suffixes);
}

#endif
