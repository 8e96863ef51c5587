// SPDX-License-Identifier: BSD-3-Clause
// `brume`: the command line front end of the Brume toolkit.
#include "BrumeRender.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace
{
const char* Usage = R"(usage: brume render [SCENE] -o OUTPUT [options]

Renders a scene with participating media in three phases (particle tracing,
radiance reconstruction, slice rendering). Without SCENE, renders the built-in
default scene (a Cornell box around a cube of forward-scattering fog).

  -o, --output FILE   out.png (tone-mapped: exposure, clamp, sRGB curve) or
                      out.vti (linear float RGB radiance, point array 'Radiance')
  --particles N       particles traced from the lights (default 1000000)
  --seed S            seed of the particles' random streams (default 0)
  --size WxH          image size in pixels (default 512x512)
  --exposure E        PNG exposure multiplier (default 1)
  --threshold T       radiosity threshold of the density estimation, in
                      particles (default 128)
  --timings           print the time of each phase (as the paper's Table 1)
  -h, --help          show this help
)";

int UsageError(const std::string& message)
{
  std::cerr << "brume: " << message << "\n\n" << Usage;
  return 2;
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

bool ParseDouble(const std::string& text, double minimum, double maximum, double& value)
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
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    return UsageError("missing command");
  }
  const std::string command = argv[1];
  if (command == "-h" || command == "--help" || command == "help")
  {
    std::cout << Usage;
    return 0;
  }
  if (command != "render")
  {
    return UsageError("unknown command '" + command + "'");
  }
  RenderOptions options;
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&](std::string& out)
    {
      if (i + 1 >= argc)
      {
        return false;
      }
      out = argv[++i];
      return true;
    };
    std::string v;
    if (arg == "-h" || arg == "--help")
    {
      std::cout << Usage;
      return 0;
    }
    else if (arg == "-o" || arg == "--output")
    {
      if (!value(options.Output) || options.Output.empty())
      {
        return UsageError(arg + " needs a file name");
      }
    }
    else if (arg == "--particles")
    {
      long long n = 0;
      if (!value(v) || !ParseInteger(v, 1, 10000000000LL, n))
      {
        return UsageError("--particles needs an integer in [1, 1e10]");
      }
      options.Particles = n;
    }
    else if (arg == "--seed")
    {
      long long s = 0;
      if (!value(v) || !ParseInteger(v, 0, 9223372036854775807LL, s))
      {
        return UsageError("--seed needs a non-negative integer");
      }
      options.Seed = static_cast<std::uint64_t>(s);
    }
    else if (arg == "--size")
    {
      const auto x = value(v) ? v.find('x') : std::string::npos;
      long long w = 0, h = 0;
      if (x == std::string::npos || !ParseInteger(v.substr(0, x), 1, 16384, w) ||
        !ParseInteger(v.substr(x + 1), 1, 16384, h))
      {
        return UsageError("--size needs WIDTHxHEIGHT, each in [1, 16384]");
      }
      options.Width = static_cast<int>(w);
      options.Height = static_cast<int>(h);
    }
    else if (arg == "--exposure")
    {
      if (!value(v) || !ParseDouble(v, 0.0, 1e12, options.Exposure))
      {
        return UsageError("--exposure needs a non-negative number");
      }
    }
    else if (arg == "--threshold")
    {
      if (!value(v) || !ParseDouble(v, 1e-6, 1e12, options.Threshold))
      {
        return UsageError("--threshold needs a positive number");
      }
    }
    else if (arg == "--timings")
    {
      options.Timings = true;
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      return UsageError("unknown option '" + arg + "'");
    }
    else if (options.Scene.empty())
    {
      options.Scene = arg;
    }
    else
    {
      return UsageError("more than one SCENE given ('" + options.Scene + "', '" + arg + "')");
    }
  }
  if (options.Output.empty())
  {
    return UsageError("missing -o OUTPUT");
  }
  return RunRender(options);
}
