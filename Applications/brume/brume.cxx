// SPDX-License-Identifier: BSD-3-Clause
// `brume`: the command line front end of the Brume toolkit.
#include "BrumeCommands.h"
#include "BrumeRender.h"
#include "BrumeThreads.h"
#include "BrumeView.h"

#include "vtkBrumeProcesses.h"
#include "vtkVersion.h"

#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
const char* General = R"(usage: brume render [SCENE] -o OUTPUT [options]
       brume view [SCENE] [options]
       brume validate slab --albedo A --optical-thickness B --g G [options]
       brume bench [--particles N] [--seed S]
       brume chart [-o chart.png] [--csv chart.csv] [options]
       brume --version

Renders scenes with participating media in the three phases of Jimenez &
Pueyo (2003): particle tracing, radiance reconstruction, slice rendering.
'brume COMMAND --help' describes a command.
)";

const char* RenderHelp = R"(usage: brume render [SCENE] -o OUTPUT [options]

Renders a scene with participating media in three phases (particle tracing,
radiance reconstruction, slice rendering). SCENE is a scene file
(Data/scenes/README.md); without it, the built-in default scene (a Cornell
box around a cube of forward-scattering fog). The scene file's render
settings are the defaults of the options below.

  -o, --output FILE   out.png (tone-mapped: exposure, clamp, sRGB curve) or
                      out.vti (linear float RGB radiance, point array 'Radiance')
  --particles N       particles traced from the lights (default 1000000)
  --seed S            seed of the particles' random streams (default 0)
  --size WxH          image size in pixels (default 512x512)
  --exposure E        PNG exposure multiplier (default 1)
  --threshold T       radiosity threshold of the density estimation, in
                      particles (default 128)
  --timings           print the time of each phase (as the paper's Table 1)
  --reference         render with the unbiased path tracer instead (no
                      display needed); .vti adds the per-pixel 'Variance'
  --spp N             samples per pixel of --reference (default 64)
)";

const char* ViewHelp = R"(usage: brume view [SCENE] [options]

Opens an interactive window (trackball camera) on a scene (default: the
built-in one). Particles are traced once; on every camera change only the
view-dependent textures (anisotropic media, glossy surfaces) are updated,
incrementally, then the frame is rendered. With --orbit the camera circles
the scene instead, off screen, and the frame times are printed.

  --particles N       particles traced at the start (default 1000000)
  --seed S            seed of the particles' random streams (default 0)
  --size WxH          window size (default 512x512)
  --exposure E        display exposure (default 1)
  --threshold T       radiosity threshold, in particles (default 128)
  --mode paper|sh     media: per-view reconstruction as in the paper
                      (default), or spherical harmonics evaluated toward the
                      eye by the slice mapper (a view change costs no
                      reconstruction)
  --order N           spherical-harmonics order, 1 to 3 (default 3)
  --sh-evaluation voxel|fragment
                      where sh media are evaluated toward the eye: once per
                      view and voxel (default; cheapest under Mesa), or per
                      fragment in the slice shader (no work on a view change)
  --keys KEYS         keys pressed at the start (p, d, m; and s with
                      --exit-after), e.g. --keys pp
  --exit-after N      interactive window driven by a timer: press the --keys,
                      turn the camera 5 degrees a frame for N frames, quit
                      and print the work done (a test of the interactive path)
  --no-overlay        hide the text overlay
  --orbit N           render N frames around the focal point (no window
                      interaction, needs a display: xvfb-run -a) and print
                      the median and 95th percentile of the update and
                      render times, and the textures recomputed meanwhile
  --frames-out DIR    with --orbit: write DIR/frame_NNNN.png
  --csv FILE          with --orbit: per-frame times (frame,update_ms,render_ms)

Keys: p  more particles (doubles the count; the new particles are added to
         the existing histograms)
      d  switch the media between per-view textures and spherical harmonics
      m  show or hide the media
      s  save the window to brume-view-NNNN.png
      q  quit
)";

const char* ValidateHelp =
  R"(usage: brume validate slab --albedo A --optical-thickness B --g G [--particles N] [--seed S]

Traces a collimated beam at normal incidence onto a laterally infinite,
index-matched slab (sigma_t = 1, thickness B, albedo A, Henyey-Greenstein
g = G) and prints a CSV header and the fractions of the incident power
reflected after scattering, transmitted after scattering and transmitted
unscattered, each with its Monte Carlo standard error (default 1000000
particles).
)";

const char* BenchHelp = R"(usage: brume bench [--particles N] [--seed S]

Traces the built-in scene (default 1000000 particles) and casts the same rays
through Embree alone; prints particles/s, hits/s, the ratio of the ray
throughputs and the peak memory per stored hit; then the reconstruction's
full and per-view times and, with a display, frame times against
vtkGPUVolumeRayCastMapper.
)";

const char* ChartHelp = R"(usage: brume chart [-o chart.png] [--csv chart.csv] [options]

Renders the built-in scene with the three-phase pipeline at a ladder of
particle budgets (media per view, as in the paper, and as spherical
harmonics) and with the path tracer at a ladder of samples per pixel,
measures each image's error against a converged reference (cached on disk)
and draws error against time, log-log, with VTK's charts. Needs a display
(xvfb-run -a).

  -o FILE             the chart (PNG, default chart.png)
  --csv FILE          the measurements (default chart.csv): method (pipeline,
                      pipeline-new-view, pipeline-sh, pipeline-sh-new-view,
                      path-tracer), budget, seconds, rel_mae, rel_rmse,
                      rel_mae_medium, rel_rmse_medium
  --size WxH          image size (default 128x128)
  --particles A:B     the pipeline's ladder, by powers of 10 (default 10000:10000000)
  --max-spp N         the path tracer's ladder, by powers of 4 (default 1024)
  --sh-order N        order of the spherical-harmonics rows, 1 to 3 (default 3)
  --reference-spp N   samples per pixel of the converged reference (default 16384)
  --cache DIR         where converged references are kept (default
                      $XDG_CACHE_HOME/brume or ~/.cache/brume)
  --sweep             the stability sweep instead: g, optical thickness,
                      albedo, particle count (up to the --particles maximum),
                      glossy and mirror floor, one at a time; per case the
                      pipeline's error and the path tracer's at the same time
                      (CSV: parameter, value, pipeline_seconds,
                      pipeline_rel_mae, pathtracer_spp, pathtracer_seconds,
                      pathtracer_rel_mae, finite, pipeline_sh_rel_mae)
)";

// The help of the command being parsed (for usage errors).
const char* Usage = General;

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

// Whether -h or --help is among a sub-command's arguments.
bool WantsHelp(int argc, char* argv[])
{
  for (int i = 2; i < argc; ++i)
  {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help")
    {
      return true;
    }
  }
  return false;
}

// Walks the options of a sub-command.
class Arguments
{
public:
  Arguments(int argc, char* argv[], int first)
    : Argc(argc)
    , Argv(argv)
    , Index(first - 1)
  {
  }
  bool Next(std::string& arg)
  {
    if (++this->Index >= this->Argc)
    {
      return false;
    }
    arg = this->Argv[this->Index];
    return true;
  }
  bool Value(std::string& out)
  {
    if (this->Index + 1 >= this->Argc)
    {
      return false;
    }
    out = this->Argv[++this->Index];
    return true;
  }

private:
  int Argc;
  char** Argv;
  int Index;
};

int ParseSeed(Arguments& args, std::uint64_t& seed)
{
  std::string v;
  long long s = 0;
  if (!args.Value(v) || !ParseInteger(v, 0, 9223372036854775807LL, s))
  {
    return UsageError("--seed needs a non-negative integer");
  }
  seed = static_cast<std::uint64_t>(s);
  return 0;
}

int ParseParticles(Arguments& args, long long& particles)
{
  std::string v;
  if (!args.Value(v) || !ParseInteger(v, 1, 10000000000LL, particles))
  {
    return UsageError("--particles needs an integer in [1, 1e10]");
  }
  return 0;
}

// Options shared by render and view: the scene and how it is traced and
// shown. 1 when `arg` is not one of them, else 0 or a usage error's code.
int ParseSceneOption(Arguments& args, const std::string& arg, RenderOptions& options)
{
  std::string v;
  if (arg == "--particles")
  {
    options.ParticlesSet = true;
    return ParseParticles(args, options.Particles);
  }
  if (arg == "--seed")
  {
    options.SeedSet = true;
    return ParseSeed(args, options.Seed);
  }
  if (arg == "--size")
  {
    const auto x = args.Value(v) ? v.find('x') : std::string::npos;
    long long w = 0, h = 0;
    if (x == std::string::npos || !ParseInteger(v.substr(0, x), 1, 16384, w) ||
      !ParseInteger(v.substr(x + 1), 1, 16384, h))
    {
      return UsageError("--size needs WIDTHxHEIGHT, each in [1, 16384]");
    }
    options.Width = static_cast<int>(w);
    options.Height = static_cast<int>(h);
    options.SizeSet = true;
    return 0;
  }
  if (arg == "--exposure")
  {
    if (!args.Value(v) || !ParseDouble(v, 0.0, 1e12, options.Exposure))
    {
      return UsageError("--exposure needs a non-negative number");
    }
    options.ExposureSet = true;
    return 0;
  }
  if (arg == "--threshold")
  {
    if (!args.Value(v) || !ParseDouble(v, 1e-6, 1e12, options.Threshold))
    {
      return UsageError("--threshold needs a positive number");
    }
    options.ThresholdSet = true;
    return 0;
  }
  if (!arg.empty() && arg[0] == '-')
  {
    return 1;
  }
  if (!options.Scene.empty())
  {
    return UsageError("more than one SCENE given ('" + options.Scene + "', '" + arg + "')");
  }
  options.Scene = arg;
  return 0;
}

int Render(int argc, char* argv[])
{
  Usage = RenderHelp;
  if (WantsHelp(argc, argv))
  {
    std::cout << Usage;
    return 0;
  }
  RenderOptions options;
  Arguments args(argc, argv, 2);
  std::string arg, v;
  while (args.Next(arg))
  {
    int rc = 0;
    if (arg == "-h" || arg == "--help")
    {
      std::cout << Usage;
      return 0;
    }
    else if (arg == "-o" || arg == "--output")
    {
      if (!args.Value(options.Output) || options.Output.empty())
      {
        return UsageError(arg + " needs a file name");
      }
    }
    else if (arg == "--timings")
    {
      options.Timings = true;
    }
    else if (arg == "--reference")
    {
      options.Reference = true;
    }
    else if (arg == "--spp")
    {
      long long spp = 0;
      if (!args.Value(v) || !ParseInteger(v, 1, 1000000, spp))
      {
        return UsageError("--spp needs an integer in [1, 1e6]");
      }
      options.SamplesPerPixel = static_cast<int>(spp);
    }
    else if ((rc = ParseSceneOption(args, arg, options)) == 1)
    {
      return UsageError("unknown option '" + arg + "'");
    }
    if (rc != 0)
    {
      return rc;
    }
  }
  if (options.Output.empty())
  {
    return UsageError("missing -o OUTPUT");
  }
  return RunRender(options);
}

int View(int argc, char* argv[])
{
  Usage = ViewHelp;
  if (WantsHelp(argc, argv))
  {
    std::cout << Usage;
    return 0;
  }
  ViewOptions options;
  Arguments args(argc, argv, 2);
  std::string arg, v;
  while (args.Next(arg))
  {
    long long n = 0;
    int rc = 0;
    if (arg == "--mode")
    {
      if (!args.Value(v) || (v != "paper" && v != "sh"))
      {
        return UsageError("--mode needs 'paper' or 'sh'");
      }
      options.Directional = v == "sh";
    }
    else if (arg == "--order")
    {
      if (!args.Value(v) || !ParseInteger(v, 1, 3, n))
      {
        return UsageError("--order needs 1, 2 or 3");
      }
      options.Order = static_cast<int>(n);
    }
    else if (arg == "--orbit")
    {
      if (!args.Value(v) || !ParseInteger(v, 1, 100000, n))
      {
        return UsageError("--orbit needs a number of frames in [1, 100000]");
      }
      options.Orbit = static_cast<int>(n);
    }
    else if (arg == "--frames-out" || arg == "--csv")
    {
      if (!args.Value(v) || v.empty())
      {
        return UsageError(arg + " needs a path");
      }
      (arg == "--csv" ? options.Csv : options.FramesOut) = v;
    }
    else if (arg == "--sh-evaluation")
    {
      if (!args.Value(v) || (v != "voxel" && v != "fragment"))
      {
        return UsageError("--sh-evaluation needs 'voxel' or 'fragment'");
      }
      options.PerFragment = v == "fragment";
    }
    else if (arg == "--keys")
    {
      if (!args.Value(options.Keys))
      {
        return UsageError("--keys needs the keys to press");
      }
    }
    else if (arg == "--exit-after")
    {
      if (!args.Value(v) || !ParseInteger(v, 1, 100000, n))
      {
        return UsageError("--exit-after needs a number of frames in [1, 100000]");
      }
      options.ExitAfter = static_cast<int>(n);
    }
    else if (arg == "--no-overlay")
    {
      options.Overlay = false;
    }
    else if ((rc = ParseSceneOption(args, arg, options.Render)) == 1)
    {
      return UsageError("unknown option '" + arg + "'");
    }
    if (rc != 0)
    {
      return rc;
    }
  }
  if (options.Orbit == 0 && (!options.FramesOut.empty() || !options.Csv.empty()))
  {
    return UsageError("--frames-out and --csv go with --orbit");
  }
  if (options.Orbit > 0 && options.ExitAfter > 0)
  {
    return UsageError("--exit-after is for the interactive window, not --orbit");
  }
  for (const char key : options.Keys)
  {
    if (key != 'p' && key != 'd' && key != 'm' && !(key == 's' && options.ExitAfter > 0))
    {
      return UsageError(
        std::string("--keys accepts p, d and m (and s with --exit-after), not '") + key + "'");
    }
  }
  return RunView(options);
}

int Validate(int argc, char* argv[])
{
  Usage = ValidateHelp;
  if (WantsHelp(argc, argv))
  {
    std::cout << Usage;
    return 0;
  }
  if (argc < 3 || std::string(argv[2]) != "slab")
  {
    return UsageError("validate needs an experiment: slab");
  }
  SlabOptions options;
  bool albedo = false, thickness = false, g = false;
  Arguments args(argc, argv, 3);
  std::string arg, v;
  while (args.Next(arg))
  {
    int rc = 0;
    if (arg == "--albedo")
    {
      albedo = args.Value(v) && ParseDouble(v, 0.0, 1.0, options.Albedo);
      if (!albedo)
      {
        return UsageError("--albedo needs a number in [0, 1]");
      }
    }
    else if (arg == "--optical-thickness")
    {
      thickness = args.Value(v) && ParseDouble(v, 1e-9, 1e4, options.OpticalThickness);
      if (!thickness)
      {
        return UsageError("--optical-thickness needs a number in (0, 1e4]");
      }
    }
    else if (arg == "--g")
    {
      g = args.Value(v) && ParseDouble(v, -0.999999, 0.999999, options.G);
      if (!g)
      {
        return UsageError("--g needs a number in (-1, 1)");
      }
    }
    else if (arg == "--particles")
    {
      rc = ParseParticles(args, options.Particles);
    }
    else if (arg == "--seed")
    {
      rc = ParseSeed(args, options.Seed);
    }
    else
    {
      return UsageError("unknown option '" + arg + "'");
    }
    if (rc != 0)
    {
      return rc;
    }
  }
  if (!albedo || !thickness || !g)
  {
    return UsageError("validate slab needs --albedo, --optical-thickness and --g");
  }
  if (options.Particles < 2)
  {
    return UsageError("validate slab needs at least 2 particles for a standard error");
  }
  return RunValidateSlab(options);
}

int Chart(int argc, char* argv[])
{
  Usage = ChartHelp;
  if (WantsHelp(argc, argv))
  {
    std::cout << Usage;
    return 0;
  }
  ChartOptions options;
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  options.CacheDirectory =
    xdg && *xdg ? std::string(xdg) + "/brume" : std::string(home ? home : ".") + "/.cache/brume";
  Arguments args(argc, argv, 2);
  std::string arg, v;
  while (args.Next(arg))
  {
    long long a = 0, b = 0;
    if (arg == "-o" || arg == "--output")
    {
      if (!args.Value(options.Output) || options.Output.empty())
      {
        return UsageError(arg + " needs a file name");
      }
    }
    else if (arg == "--csv")
    {
      if (!args.Value(options.Csv) || options.Csv.empty())
      {
        return UsageError("--csv needs a file name");
      }
    }
    else if (arg == "--cache")
    {
      if (!args.Value(options.CacheDirectory) || options.CacheDirectory.empty())
      {
        return UsageError("--cache needs a directory");
      }
    }
    else if (arg == "--size")
    {
      const auto x = args.Value(v) ? v.find('x') : std::string::npos;
      if (x == std::string::npos || !ParseInteger(v.substr(0, x), 1, 4096, a) ||
        !ParseInteger(v.substr(x + 1), 1, 4096, b))
      {
        return UsageError("--size needs WIDTHxHEIGHT, each in [1, 4096]");
      }
      options.Width = static_cast<int>(a);
      options.Height = static_cast<int>(b);
    }
    else if (arg == "--particles")
    {
      const auto colon = args.Value(v) ? v.find(':') : std::string::npos;
      if (colon == std::string::npos || !ParseInteger(v.substr(0, colon), 1, 10000000000LL, a) ||
        !ParseInteger(v.substr(colon + 1), a, 10000000000LL, b))
      {
        return UsageError("--particles needs MIN:MAX with 1 <= MIN <= MAX <= 1e10");
      }
      options.MinParticles = a;
      options.MaxParticles = b;
    }
    else if (arg == "--sweep")
    {
      options.Sweep = true;
    }
    else if (arg == "--sh-order")
    {
      if (!args.Value(v) || !ParseInteger(v, 1, 3, a))
      {
        return UsageError("--sh-order needs 1, 2 or 3");
      }
      options.ShOrder = static_cast<int>(a);
    }
    else if (arg == "--max-spp" || arg == "--reference-spp")
    {
      if (!args.Value(v) || !ParseInteger(v, 1, 1000000, a))
      {
        return UsageError(arg + " needs an integer in [1, 1e6]");
      }
      (arg == "--max-spp" ? options.MaxSamples : options.ReferenceSamples) = static_cast<int>(a);
    }
    else
    {
      return UsageError("unknown option '" + arg + "'");
    }
  }
  return RunChart(options);
}

int Bench(int argc, char* argv[])
{
  Usage = BenchHelp;
  if (WantsHelp(argc, argv))
  {
    std::cout << Usage;
    return 0;
  }
  BenchOptions options;
  Arguments args(argc, argv, 2);
  std::string arg;
  while (args.Next(arg))
  {
    int rc = 0;
    if (arg == "--particles")
    {
      rc = ParseParticles(args, options.Particles);
    }
    else if (arg == "--seed")
    {
      rc = ParseSeed(args, options.Seed);
    }
    else
    {
      return UsageError("unknown option '" + arg + "'");
    }
    if (rc != 0)
    {
      return rc;
    }
  }
  return RunBench(options);
}
}

int main(int argc, char* argv[])
{
  const vtkBrumeProcesses::Session processes(&argc, &argv); // MPI, when mpirun started brume
  if (argc < 2)
  {
    return UsageError("missing command");
  }
  const std::string command = argv[1];
  BrumeUseAllCores();
  if (command == "-h" || command == "--help" || command == "help")
  {
    std::cout << General;
    return 0;
  }
  if (command == "--version" || command == "version")
  {
    std::cout << "brume " << BRUME_VERSION << " (VTK " << vtkVersion::GetVTKVersionFull() << ")\n";
    return 0;
  }
  if (command == "render")
  {
    return Render(argc, argv);
  }
  if (command == "view")
  {
    return View(argc, argv);
  }
  if (command == "validate")
  {
    return Validate(argc, argv);
  }
  if (command == "bench")
  {
    return Bench(argc, argv);
  }
  if (command == "chart")
  {
    return Chart(argc, argv);
  }
  return UsageError("unknown command '" + command + "'");
}
