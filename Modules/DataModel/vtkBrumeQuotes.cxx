// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeQuotes.h"

#include <algorithm>
#include <cctype>

namespace
{
bool WordCharacter(char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}
}

std::string vtkBrumeBoundQuotes(const std::string& message, std::size_t most)
{
  // A quote opens after a non-word character ("key 'x'", not "the light's")
  // and closes before one; what lies between is shortened.
  std::string out;
  out.reserve(std::min(message.size(), static_cast<std::size_t>(4096)));
  std::size_t at = 0;
  while (at < message.size())
  {
    std::size_t open = message.find('\'', at);
    while (open != std::string::npos && open > 0 && WordCharacter(message[open - 1]))
    {
      open = message.find('\'', open + 1);
    }
    std::size_t close = open == std::string::npos ? open : message.find('\'', open + 1);
    while (
      close != std::string::npos && close + 1 < message.size() && WordCharacter(message[close + 1]))
    {
      close = message.find('\'', close + 1);
    }
    if (close == std::string::npos)
    {
      // No quoted part left: the rest as it is, unless it is itself huge.
      constexpr std::size_t Rest = 1000;
      const std::size_t length = message.size() - at;
      out.append(message, at, std::min(length, Rest));
      if (length > Rest)
      {
        out += "...";
      }
      break;
    }
    out.append(message, at, open + 1 - at);
    const std::size_t length = close - open - 1;
    if (length > most)
    {
      const std::size_t head = most / 2, tail = most - head - 3;
      out.append(message, open + 1, head);
      out += "...";
      out.append(message, close - tail, tail);
    }
    else
    {
      out.append(message, open + 1, length);
    }
    out += '\'';
    at = close + 1;
  }
  return out;
}
