// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeQuotes.h"

#include <algorithm>

std::string vtkBrumeBoundQuotes(const std::string& message, std::size_t most)
{
  std::string out;
  out.reserve(std::min(message.size(), static_cast<std::size_t>(4096)));
  std::size_t at = 0;
  while (at < message.size())
  {
    const std::size_t open = message.find('\'', at);
    const std::size_t close = open == std::string::npos ? open : message.find('\'', open + 1);
    if (close == std::string::npos)
    {
      // The rest, an unbalanced quote included, bounded as a quoted part.
      const std::string rest = message.substr(at);
      if (rest.size() > 2 * most)
      {
        out += rest.substr(0, most) + "...";
      }
      else
      {
        out += rest;
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
