// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeOptions.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace BrumeOptions
{
namespace
{
std::string Refused(const std::string& expected, const std::string& text)
{
  return "expected " + expected + ", not '" + text + "'";
}

// A validator without a description: the help shows the option's type name
// alone, and the option's description says the range.
CLI::Validator MakeValidator(std::function<std::string(std::string&)> check)
{
  return CLI::Validator(std::move(check), std::string());
}
}

bool ParseInteger(const std::string& text, long long minimum, long long maximum, long long& value)
{
  if (text.empty())
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || *end != '\0' || v < minimum || v > maximum)
  {
    return false;
  }
  value = v;
  return true;
}

bool ParseNumber(const std::string& text, double minimum, double maximum, double& value)
{
  if (text.empty())
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (errno != 0 || *end != '\0' || !(v >= minimum && v <= maximum))
  {
    return false;
  }
  value = v;
  return true;
}

bool ParseSize(const std::string& text, int maximum, int& width, int& height)
{
  const auto x = text.find('x');
  long long w = 0, h = 0;
  if (x == std::string::npos || !ParseInteger(text.substr(0, x), 1, maximum, w) ||
    !ParseInteger(text.substr(x + 1), 1, maximum, h))
  {
    return false;
  }
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return true;
}

bool ParseRange(
  const std::string& text, long long minimum, long long maximum, long long& low, long long& high)
{
  const auto colon = text.find(':');
  long long a = 0, b = 0;
  if (colon == std::string::npos || !ParseInteger(text.substr(0, colon), minimum, maximum, a) ||
    !ParseInteger(text.substr(colon + 1), a, maximum, b))
  {
    return false;
  }
  low = a;
  high = b;
  return true;
}

std::string CheckKeys(const std::string& keys, bool exitAfter)
{
  for (const char key : keys)
  {
    if (key != 'p' && key != 'd' && key != 'm' && key != 'n' && key != 'b' &&
      !(key == 's' && exitAfter))
    {
      return std::string("--keys accepts p, d, m, n and b (and s with --exit-after), not '") + key +
        "'";
    }
  }
  return std::string();
}

CLI::Validator Integer(long long minimum, long long maximum, const std::string& expected)
{
  return MakeValidator(
    [=](std::string& text)
    {
      long long value = 0;
      if (!ParseInteger(text, minimum, maximum, value))
      {
        return Refused(expected, text);
      }
      text = std::to_string(value); // CLI11 reads "010" as octal
      return std::string();
    });
}

CLI::Validator Number(double minimum, double maximum, const std::string& expected)
{
  return MakeValidator(
    [=](std::string& text)
    {
      double value = 0.0;
      if (!ParseNumber(text, minimum, maximum, value))
      {
        return Refused(expected, text);
      }
      char exact[32];
      std::snprintf(exact, sizeof(exact), "%.17g", value); // reads back as the same double
      text = exact;
      return std::string();
    });
}

CLI::Validator Size(int maximum)
{
  return MakeValidator(
    [=](std::string& text)
    {
      int width = 0, height = 0;
      return ParseSize(text, maximum, width, height)
        ? std::string()
        : Refused("WIDTHxHEIGHT, each in [1, " + std::to_string(maximum) + "]", text);
    });
}

CLI::Validator Range(long long minimum, long long maximum, const std::string& expected)
{
  return MakeValidator(
    [=](std::string& text)
    {
      long long low = 0, high = 0;
      return ParseRange(text, minimum, maximum, low, high) ? std::string()
                                                           : Refused(expected, text);
    });
}

CLI::Validator OneOf(const std::vector<std::string>& choices)
{
  std::string expected;
  for (std::size_t i = 0; i < choices.size(); ++i)
  {
    expected += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + ("'" + choices[i] + "'");
  }
  return MakeValidator(
    [=](std::string& text)
    {
      for (const std::string& choice : choices)
      {
        if (text == choice)
        {
          return std::string();
        }
      }
      return Refused(expected, text);
    });
}

CLI::Validator NotEmpty(const std::string& expected)
{
  return MakeValidator(
    [=](std::string& text) { return text.empty() ? Refused(expected, text) : std::string(); });
}

CLI::Validator Suffix(const std::vector<std::string>& suffixes)
{
  std::string expected = "a file name ending in";
  for (std::size_t i = 0; i < suffixes.size(); ++i)
  {
    expected += (i == 0 ? " " : i + 1 == suffixes.size() ? " or " : ", ") + suffixes[i];
  }
  return MakeValidator(
    [=](std::string& text)
    {
      for (const std::string& suffix : suffixes)
      {
        if (text.size() >= suffix.size() &&
          text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0)
        {
          return std::string();
        }
      }
      return Refused(expected, text);
    });
}
}
