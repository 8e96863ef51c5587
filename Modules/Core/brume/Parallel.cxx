// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Parallel.h"

namespace brume
{

ParallelFor SerialFor()
{
  return [](std::size_t begin, std::size_t end,
           const std::function<void(std::size_t, std::size_t)>& body)
  {
    if (begin < end)
    {
      body(begin, end);
    }
  };
}

} // namespace brume
