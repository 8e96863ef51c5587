// SPDX-License-Identifier: BSD-3-Clause
// `brume`'s command line, parsed without running anything: the values and
// defaults each command receives, which options record that they were given,
// the cross-option checks, and the exit code and message of usage errors.
#include "BrumeCommandLine.h"

#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkNew.h"

#include <array>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Parsed
{
  int Code = 0;
  BrumeCommandLine Line;
  std::string Out, Err;
};

Parsed Parse(std::vector<std::string> args)
{
  args.insert(args.begin(), "brume");
  std::vector<char*> argv;
  for (std::string& arg : args)
  {
    argv.push_back(&arg[0]);
  }
  argv.push_back(nullptr);
  Parsed parsed;
  std::ostringstream out, err;
  parsed.Code = ParseCommandLine(static_cast<int>(args.size()), argv.data(), parsed.Line, out, err);
  parsed.Out = out.str();
  parsed.Err = err.str();
  return parsed;
}

int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

using Command = BrumeCommandLine::Command;

// A usage error: exit code 2, nothing to run, and `brume: ...` naming `names`.
void ExpectUsageError(const std::vector<std::string>& args, const std::string& names)
{
  std::string line;
  for (const std::string& arg : args)
  {
    line += " " + arg;
  }
  const Parsed p = Parse(args);
  Check(p.Code == 2 && p.Line.Run == Command::None, "brume" + line + ": exit code 2");
  Check(p.Err.rfind("brume: ", 0) == 0 && p.Err.find(names) != std::string::npos &&
      p.Err.find("--help") != std::string::npos,
    "brume" + line + ": the message names '" + names + "' and points at --help:\n" + p.Err);
}

void TestRender()
{
  Parsed p = Parse({ "render", "-o", "x.png" });
  const RenderOptions& r = p.Line.Render;
  Check(p.Code == -1 && p.Line.Run == Command::Render, "render -o x.png runs");
  Check(r.Output == "x.png" && r.Scene.empty() && !r.Timings && !r.Reference &&
      r.SamplesPerPixel == 64 && r.Supersample == 1,
    "render defaults");
  Check(!r.Particles && !r.Seed && !r.Size && !r.Exposure && !r.Threshold && !r.DirectLight &&
      !r.CentroidMatching && !r.MediumAim && !r.SplitHeavy && !r.Batch && !r.MemoryLimit &&
      !r.MaxDepth,
    "render: options not given stay unset (the scene file's settings, else the filters' "
    "defaults)");

  p = Parse({ "render", "scene.json", "--particles", "010", "--seed", "7", "--size", "64x32",
    "--exposure", "2.5", "--threshold", "0.1", "--timings", "--reference", "--spp", "16",
    "--output", "x.vti", "--particles", "20" });
  const RenderOptions& g = p.Line.Render;
  Check(p.Code == -1 && g.Scene == "scene.json" && g.Output == "x.vti", "render SCENE --output");
  Check(g.Particles == 20 && g.Seed == 7u && g.Size == std::array<int, 2>{ 64, 32 } &&
      g.Exposure == 2.5 && g.Threshold == 0.1 && g.Timings && g.Reference &&
      g.SamplesPerPixel == 16,
    "render: the values given, the last of a repeated option");
  p = Parse({ "render", "-o", "x.png", "--no-direct-light", "--no-split", "--no-centroid-matching",
    "--aim", "0.5", "--batch", "1000", "--memory-limit", "2", "--max-depth", "3" });
  const RenderOptions& f = p.Line.Render;
  Check(p.Code == -1 && f.DirectLight == false && f.SplitHeavy == false &&
      f.CentroidMatching == false && f.MediumAim == 0.5 && f.Batch == 1000 &&
      f.MemoryLimit == 2.0 && f.MaxDepth == 3,
    "render: flags and the tracer's options are recorded");
  Check(Parse({ "render", "-o", "x.png", "--particles", "010" }).Line.Render.Particles == 10,
    "integers are decimal");
  // The help states the defaults of the objects that own them.
  vtkNew<vtkBrumePipeline> defaults;
  const std::string help = Parse({ "render", "--help" }).Out;
  for (const std::string& stated :
    { "(default " + std::to_string(defaults->GetTracer()->GetNumberOfParticles()) + ")",
      "(default " + std::to_string(defaults->GetSize()[0]) + "x" +
        std::to_string(defaults->GetSize()[1]) + ")",
      "(default " + std::to_string(defaults->GetTracer()->GetMaximumDepth()) + ")" })
  {
    Check(help.find(stated) != std::string::npos,
      "render --help states the owner's default " + stated + ":\n" + help);
  }

  ExpectUsageError({ "render" }, "--output");
  ExpectUsageError({ "render", "-o" }, "--output");
  ExpectUsageError({ "render", "-o", "x.jpg" }, ".png or .vti");
  ExpectUsageError({ "render", "-o", "x.png", "--bogus" }, "--bogus");
  ExpectUsageError({ "render", "a.json", "b.json", "-o", "x.png" }, "b.json");
  ExpectUsageError({ "render", "-o", "x.png", "--particles", "12abc" }, "--particles");
  ExpectUsageError({ "render", "-o", "x.png", "--particles", "-5" }, "--particles");
  ExpectUsageError({ "render", "-o", "x.png", "--particles", "20000000000" }, "--particles");
  ExpectUsageError({ "render", "-o", "x.png", "--seed", "0x10" }, "--seed");
  ExpectUsageError({ "render", "-o", "x.png", "--size", "10" }, "--size");
  ExpectUsageError({ "render", "-o", "x.png", "--size", "0x100" }, "--size");
  ExpectUsageError({ "render", "-o", "x.png", "--size", "16385x16" }, "--size");
  ExpectUsageError({ "render", "-o", "x.png", "--exposure", "-1" }, "--exposure");
  ExpectUsageError({ "render", "-o", "x.png", "--threshold", "0" }, "--threshold");
  ExpectUsageError({ "render", "-o", "x.png", "--spp", "0" }, "--spp");
  ExpectUsageError({ "render", "-o", "x.png", "--particles" }, "--particles");
}

void TestView()
{
  Parsed p = Parse({ "view" });
  const ViewOptions& v = p.Line.View;
  Check(p.Code == -1 && p.Line.Run == Command::View && !v.Directional && v.Order == 3 &&
      !v.PerFragment && v.Orbit == 0 && v.Keys.empty() && v.Overlay && v.ExitAfter == 0 &&
      !v.Render.Size,
    "view defaults");

  p = Parse({ "view", "s.json", "--mode", "sh", "--order", "2", "--sh-evaluation", "fragment",
    "--no-overlay", "--keys", "pds", "--exit-after", "3", "--size", "96x64" });
  const ViewOptions& w = p.Line.View;
  Check(p.Code == -1 && w.Render.Scene == "s.json" && w.Directional && w.Order == 2 &&
      w.PerFragment && !w.Overlay && w.Keys == "pds" && w.ExitAfter == 3 &&
      w.Render.Size == std::array<int, 2>{ 96, 64 },
    "view: the values given; s with --exit-after");
  p = Parse({ "view", "--orbit", "6", "--frames-out", "frames", "--csv", "o.csv", "--keys", "ppdm",
    "--mode", "paper" });
  Check(p.Code == -1 && p.Line.View.Orbit == 6 && p.Line.View.FramesOut == "frames" &&
      p.Line.View.Csv == "o.csv" && !p.Line.View.Directional,
    "view --orbit with --frames-out and --csv");
  Check(Parse({ "view", "--keys", "" }).Code == -1, "view --keys ''");

  ExpectUsageError({ "view", "--mode", "fancy" }, "--mode");
  ExpectUsageError({ "view", "--order", "7" }, "--order");
  ExpectUsageError({ "view", "--sh-evaluation", "texel" }, "--sh-evaluation");
  ExpectUsageError({ "view", "--orbit", "0" }, "--orbit");
  ExpectUsageError({ "view", "--frames-out", "frames" }, "--orbit");
  ExpectUsageError({ "view", "--csv", "o.csv" }, "--orbit");
  ExpectUsageError({ "view", "--orbit", "1", "--exit-after", "2" }, "--exit-after");
  ExpectUsageError({ "view", "--orbit", "1", "--keys", "x" }, "--keys");
  ExpectUsageError({ "view", "--orbit", "1", "--keys", "s" }, "--keys");
}

void TestValidateBenchChart()
{
  Parsed p = Parse({ "validate", "slab", "--albedo", "0.5", "--optical-thickness", "2", "--g",
    "-0.5", "--particles", "2", "--seed", "3" });
  const SlabOptions& s = p.Line.Slab;
  Check(p.Code == -1 && p.Line.Run == Command::ValidateSlab && s.Albedo == 0.5 &&
      s.OpticalThickness == 2.0 && s.G == -0.5 && s.Particles == 2 && s.Seed == 3,
    "validate slab: the values given, a negative --g");
  ExpectUsageError({ "validate" }, "slab");
  ExpectUsageError({ "validate", "slab", "--albedo", "0.5", "--g", "0" }, "--optical-thickness");
  ExpectUsageError(
    { "validate", "slab", "--albedo", "1.5", "--optical-thickness", "1", "--g", "0" }, "--albedo");
  ExpectUsageError(
    { "validate", "slab", "--albedo", "0.5", "--optical-thickness", "1", "--g", "1" }, "--g");
  ExpectUsageError({ "validate", "slab", "--albedo", "0.5", "--optical-thickness", "1", "--g", "0",
                     "--particles", "1" },
    "--particles");

  p = Parse({ "bench", "--particles", "1000", "--seed", "5" });
  Check(p.Code == -1 && p.Line.Run == Command::Bench && p.Line.Bench.Particles == 1000 &&
      p.Line.Bench.Seed == 5,
    "bench: the values given");
  ExpectUsageError({ "bench", "--fast" }, "--fast");

  p = Parse({ "chart" });
  const ChartOptions& c = p.Line.Chart;
  Check(p.Code == -1 && p.Line.Run == Command::Chart && c.Output == "chart.png" &&
      c.Csv == "chart.csv" && !c.CacheDirectory.empty() && c.Width == 128 && c.Height == 128 &&
      c.MinParticles == 10000 && c.MaxParticles == 10000000 && c.MaxSamples == 1024 &&
      c.ReferenceSamples == 16384 && !c.Sweep && c.ShOrder == 3 && c.Supersample == 4 &&
      c.Scene.empty() && c.Medium.empty() && c.Surface.empty(),
    "chart defaults");
  p = Parse({ "chart", "s.json", "--medium", "fog", "--surface", "floor", "--particles", "100:1000",
    "--size", "16x8", "--sweep", "--sh-order", "2", "--max-spp", "4", "--reference-spp", "16",
    "--cache", "cache", "-o", "a.png", "--csv", "a.csv", "--supersample", "8" });
  const ChartOptions& d = p.Line.Chart;
  Check(p.Code == -1 && d.Scene == "s.json" && d.Medium == "fog" && d.Surface == "floor" &&
      d.MinParticles == 100 && d.MaxParticles == 1000 && d.Width == 16 && d.Height == 8 &&
      d.Sweep && d.ShOrder == 2 && d.MaxSamples == 4 && d.ReferenceSamples == 16 &&
      d.Supersample == 8 && d.CacheDirectory == "cache" && d.Output == "a.png" && d.Csv == "a.csv",
    "chart: the values given");
  ExpectUsageError({ "chart", "--particles", "100:10" }, "--particles");
  ExpectUsageError({ "chart", "--particles", "0:10" }, "--particles");
  ExpectUsageError({ "chart", "--particles", "10" }, "--particles");
  ExpectUsageError({ "chart", "--particles", "1:20000000000" }, "--particles");
  ExpectUsageError({ "chart", "--size", "5000x16" }, "--size");
  ExpectUsageError({ "chart", "a.json", "b.json" }, "b.json");
  ExpectUsageError({ "chart", "--supersample", "0" }, "--supersample");
  ExpectUsageError({ "chart", "--supersample", "17" }, "--supersample");
}

void TestHelp()
{
  const std::vector<std::vector<std::string>> commands = {
    { "render", "--output", "--particles", "--seed", "--size", "--exposure", "--threshold",
      "--timings", "--reference", "--spp" },
    { "view", "--mode", "--order", "--sh-evaluation", "--keys", "--exit-after", "--no-overlay",
      "--orbit", "--frames-out", "--csv", "Keys:" },
    { "validate", "--albedo", "--optical-thickness", "--g", "--particles", "--seed" },
    { "bench", "--particles", "--seed" },
    { "chart", "SCENE", "--output", "--csv", "--size", "--particles", "--max-spp", "--supersample",
      "--sh-order", "--reference-spp", "--cache", "--sweep", "--medium", "--surface" }
  };
  for (const auto& command : commands)
  {
    // Help wins over anything else given, as a bad value.
    for (const std::vector<std::string>& args : { std::vector<std::string>{ command[0], "--help" },
           std::vector<std::string>{ command[0], "--particles", "0", "-h" } })
    {
      const Parsed p = Parse(args);
      Check(p.Code == 0 && p.Line.Run == Command::None && p.Err.empty() &&
          p.Out.find("usage: brume " + command[0]) != std::string::npos,
        "brume " + command[0] + " --help");
      for (std::size_t i = 1; i < command.size(); ++i)
      {
        Check(p.Out.find(command[i]) != std::string::npos,
          "brume " + command[0] + " --help lists " + command[i]);
      }
    }
  }
  Check(Parse({ "validate", "slab", "--help" }).Out.find("--albedo") != std::string::npos,
    "brume validate slab --help");
  for (const char* help : { "--help", "-h", "help" })
  {
    const Parsed p = Parse({ help });
    Check(p.Code == 0 && p.Out.find("brume chart [SCENE]") != std::string::npos,
      std::string("brume ") + help);
  }
  for (const char* version : { "--version", "version" })
  {
    Check(Parse({ version }).Line.Run == Command::Version, std::string("brume ") + version);
  }
  ExpectUsageError({}, "missing command");
  ExpectUsageError({ "paint" }, "'paint'");
  ExpectUsageError({ "render", "--version", "-o", "x.png" }, "--version");
}
}

int TestCommandLine(int, char*[])
{
  TestRender();
  TestView();
  TestValidateBenchChart();
  TestHelp();
  if (Failures)
  {
    std::cerr << Failures << " command-line checks failed\n";
    return EXIT_FAILURE;
  }
  std::cout << "command line: every check passed\n";
  return EXIT_SUCCESS;
}
