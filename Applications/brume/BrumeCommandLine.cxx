// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeCommandLine.h"

#include "BrumeOptions.h"

#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkNew.h"

#include <CLI/CLI.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace BrumeOptions;

namespace
{
// The help of a command: its usage line(s), the paragraph that describes
// it, its arguments and options (one line each, the description in a column
// beside it), and its footer.
class BrumeFormatter : public CLI::Formatter
{
public:
  explicit BrumeFormatter(std::string usage)
    : Usage(std::move(usage))
  {
    this->column_width(22);
    this->label("Positionals", "Arguments");
  }
  std::string make_usage(const CLI::App*, std::string) const override
  {
    return "usage: " + this->Usage + "\n";
  }
  std::string make_help(
    const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override
  {
    std::string footer = this->make_footer(app);
    return this->make_usage(app, name) + "\n" + this->make_description(app) +
      this->make_positionals(app) + this->make_groups(app, mode) +
      (footer.empty() ? "" : "\n" + footer);
  }
  // "-o, --output FILE"
  std::string make_option_name(const CLI::Option* option, bool positional) const override
  {
    std::string names = CLI::Formatter::make_option_name(option, positional);
    for (std::size_t comma = names.find(','); comma != std::string::npos;
         comma = names.find(',', comma + 2))
    {
      names.insert(comma + 1, " ");
    }
    return names;
  }
  // The value's name alone: the description says the range and the default.
  std::string make_option_opts(const CLI::Option* option) const override
  {
    return option->nonpositional() && option->get_type_size() != 0 ? " " + option->get_type_name()
                                                                   : std::string();
  }

private:
  std::string Usage;
};

CLI::App* AddCommand(
  CLI::App& app, const std::string& name, const std::string& usage, const std::string& description)
{
  CLI::App* command = app.add_subcommand(name, description);
  command->formatter(std::make_shared<BrumeFormatter>(usage));
  return command;
}

// The defaults the help states, read from the objects that own them
// (vtkBrumePipeline and its filters), so that none is written twice.
struct Defaults
{
  long long Particles, Seed, MaxDepth;
  int Width, Height;
  double Exposure, Threshold, MediumAim, MemoryGiB, NativeGiB;
};

Defaults ReadDefaults()
{
  vtkNew<vtkBrumePipeline> pipeline;
  vtkBrumeLightTracer* tracer = pipeline->GetTracer();
  return { static_cast<long long>(tracer->GetNumberOfParticles()),
    static_cast<long long>(tracer->GetSeed()), tracer->GetMaximumDepth(), pipeline->GetSize()[0],
    pipeline->GetSize()[1], pipeline->GetExposure(),
    pipeline->GetReconstruction()->GetRadiosityThreshold(), tracer->GetMediumAimFraction(),
    static_cast<double>(tracer->GetMemoryLimit()) / 1073741824.0,
    static_cast<double>(pipeline->GetReconstruction()->GetEffectiveNativeMemoryLimit()) /
      1073741824.0 };
}

// A default as the help writes it: 1000000, 0.2, 512x512.
std::string Text(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

std::string Text(long long value)
{
  return std::to_string(value);
}

void AddSeed(CLI::App* command, std::uint64_t& seed, const Defaults& d)
{
  command
    ->add_option(
      "--seed", seed, "seed of the particles' random streams (default " + Text(d.Seed) + ")")
    ->transform(Integer(0, 9223372036854775807LL, "a non-negative integer"))
    ->type_name("S");
}

// What render and view say of the options they share (the default follows).
struct SceneHelp
{
  std::string Particles;
  std::string Size;
  std::string Exposure;
  std::string Threshold;
};

// The scene and how it is traced and shown (render and view). An option not
// given stays unset: the scene file's render settings, else the owning
// filter's default, give it.
void AddSceneOptions(CLI::App* command, RenderOptions& o, const SceneHelp& help, const Defaults& d)
{
  command->add_option("SCENE", o.Scene, "a scene file, or 'default' (the built-in scene)");
  command
    ->add_option_function<long long>(
      "--particles", [&o](const long long& n) { o.Particles = n; },
      help.Particles + " (default " + Text(d.Particles) + ")")
    ->transform(Integer(1, 10000000000LL, "an integer in [1, 1e10]"))
    ->type_name("N");
  command
    ->add_option_function<std::uint64_t>(
      "--seed", [&o](const std::uint64_t& seed) { o.Seed = seed; },
      "seed of the particles' random streams (default " + Text(d.Seed) + ")")
    ->transform(Integer(0, 9223372036854775807LL, "a non-negative integer"))
    ->type_name("S");
  command
    ->add_option_function<std::string>(
      "--size",
      [&o](const std::string& text)
      {
        std::array<int, 2> size{};
        if (ParseSize(text, 16384, size[0], size[1]))
        {
          o.Size = size;
        }
      },
      help.Size + " (default " + Text(static_cast<long long>(d.Width)) + "x" +
        Text(static_cast<long long>(d.Height)) + ")")
    ->transform(Size(16384))
    ->type_name("WxH");
  command
    ->add_option_function<double>(
      "--exposure", [&o](const double& exposure) { o.Exposure = exposure; },
      help.Exposure + " (default " + Text(d.Exposure) + ")")
    ->transform(Number(0.0, 1e12, "a non-negative number"))
    ->type_name("E");
  command
    ->add_option_function<double>(
      "--threshold", [&o](const double& threshold) { o.Threshold = threshold; },
      help.Threshold + " (default " + Text(d.Threshold) + ")")
    ->transform(Number(1e-6, 1e12, "a positive number"))
    ->type_name("T");
  command->add_flag_callback(
    "--no-direct-light", [&o]() { o.DirectLight = false; },
    "estimate the direct light of point, spot and\n"
    "directional lights from the particles too, instead of\n"
    "computing it with shadow rays (sharper shafts and\n"
    "shadows; the default)");
  command
    ->add_option_function<double>(
      "--aim", [&o](const double& aim) { o.MediumAim = aim; },
      "fraction of a directional light's particles aimed at\n"
      "the part of its beam that reaches the media, where it\n"
      "covers at most a quarter of the beam (a cloud over a\n"
      "wide ground, a window; default " +
        Text(d.MediumAim) +
        ", 0: the beam\n"
        "uniformly)")
    ->transform(Number(0.0, 0.99, "a number in [0, 0.99]"))
    ->type_name("F");
  command->add_flag_callback(
    "--no-split", [&o]() { o.SplitHeavy = false; },
    "under an aimed light, keep the particles emitted\n"
    "outside the aimed part whole, instead of splitting each\n"
    "into aimed particles where it heads into a medium (the\n"
    "ground's light into a cloud from many particles; the\n"
    "default)");
  command->add_flag_callback(
    "--no-centroid-matching", [&o]() { o.CentroidMatching = false; },
    "keep a medium's texel estimates as they are, instead\n"
    "of matching the texture to where each belongs (its\n"
    "region's centroid; the default, truer at a dense\n"
    "cloud's edge)");
}

void AddRender(CLI::App& app, RenderOptions& o, const Defaults& d)
{
  CLI::App* render = AddCommand(app, "render", "brume render [SCENE] -o OUTPUT [options]",
    "Renders a scene with participating media in three phases (particle tracing,\n"
    "radiance reconstruction, slice rendering). SCENE is a scene file\n"
    "(Data/scenes/README.md); without it, the built-in default scene (a Cornell\n"
    "box around a cube of forward-scattering fog). The scene file's render\n"
    "settings are the defaults of the options below.");
  render
    ->add_option("-o,--output", o.Output,
      "out.png (tone-mapped: exposure, clamp, sRGB curve) or\n"
      "out.vti (linear float RGB radiance, point array 'Radiance')")
    ->transform(Suffix({ ".png", ".vti" }))
    ->type_name("FILE")
    ->required();
  AddSceneOptions(render, o,
    { "particles traced from the lights", "image size in pixels", "PNG exposure multiplier",
      "radiosity threshold of the density estimation, in\nparticles" },
    d);
  render
    ->add_option("--supersample", o.Supersample,
      "average K x K samples of each pixel's area (K^2 frames,\n"
      "shifted on a rotated grid), as the path tracer integrates\n"
      "pixels (default 1: the pixels' centres)")
    ->transform(Integer(1, 8, "an integer in [1, 8]"))
    ->type_name("K");
  render->add_flag("--timings", o.Timings, "print the time of each phase (as the paper's Table 1)");
  render
    ->add_option_function<long long>(
      "--batch", [&o](const long long& n) { o.Batch = n; },
      "trace and bin the particles N at a time: only one\n"
      "batch's hits are held (default: all at once, or\n"
      "batches of at most 10^7 that fit --memory-limit where\n"
      "the run's hits would not; one process only)")
    ->transform(Integer(1, 10000000000LL, "an integer in [1, 1e10]"))
    ->type_name("N");
  render
    ->add_option_function<double>(
      "--memory-limit", [&o](const double& gib) { o.MemoryLimit = gib; },
      "GiB the hits of one trace may take (default " + Text(d.MemoryGiB) +
        "): a run\n"
        "whose hits would not fit is traced in batches that do")
    ->transform(Number(0.001, 1e6, "a number in [0.001, 1e6]"))
    ->type_name("GIB");
  render
    ->add_option_function<double>(
      "--native-memory", [&o](const double& gib) { o.NativeMemory = gib; },
      "GiB each heterogeneous medium's grids at its own\n"
      "resolution may take (default a quarter of half this\n"
      "machine's memory, here " +
        Text(std::round(d.NativeGiB * 10.0) / 10.0) +
        "): a medium past it is drawn\n"
        "coarsened, and a warning says so")
    ->transform(Number(0.0001, 1e6, "a number in [0.0001, 1e6]"))
    ->type_name("GIB");
  render->add_flag("--reference", o.Reference,
    "render with the unbiased path tracer instead (no\n"
    "display needed); .vti adds the per-pixel 'Variance'");
  render
    ->add_option_function<int>(
      "--time-step", [&o](const int& step) { o.TimeStep = step; },
      "of a scene that changes over time (media given as lists\n"
      "of files), render step K alone (from 0) to OUTPUT\n"
      "(default: every step, step K to OUTPUT with K before\n"
      "its suffix: out.0000.png, out.0001.png...)")
    ->transform(Integer(0, 1000000, "an integer in [0, 1e6]"))
    ->type_name("K");
  render->add_option("--spp", o.SamplesPerPixel, "samples per pixel of --reference (default 64)")
    ->transform(Integer(1, 1000000, "an integer in [1, 1e6]"))
    ->type_name("N");
  render
    ->add_option_function<int>(
      "--max-depth", [&o](const int& depth) { o.MaxDepth = depth; },
      "interactions after which particles (and --reference's\n"
      "paths) stop: 1 renders the light scattered or reflected\n"
      "once, 2 adds the light scattered twice... (default " +
        Text(d.MaxDepth) + ")")
    ->transform(Integer(1, 1000000, "an integer in [1, 1e6]"))
    ->type_name("N");
}

void AddView(CLI::App& app, ViewOptions& o, const Defaults& d)
{
  CLI::App* view = AddCommand(app, "view", "brume view [SCENE] [options]",
    "Opens an interactive window (trackball camera) on a scene (default: the\n"
    "built-in one). Particles are traced once; on every camera change only the\n"
    "view-dependent textures (anisotropic media, glossy surfaces) are updated,\n"
    "incrementally, then the frame is rendered. With --orbit the camera circles\n"
    "the scene instead, off screen, and the frame times are printed.");
  AddSceneOptions(view, o.Render,
    { "particles traced at the start", "window size", "display exposure",
      "radiosity threshold, in particles" },
    d);
  view
    ->add_option_function<std::string>(
      "--mode", [&o](const std::string& mode) { o.Directional = mode == "sh"; },
      "media: per-view reconstruction as in the paper\n"
      "(default), or spherical harmonics evaluated toward the\n"
      "eye by the slice mapper (a view change costs no\n"
      "reconstruction)")
    ->transform(OneOf({ "paper", "sh" }))
    ->type_name("paper|sh");
  view->add_option("--order", o.Order, "spherical-harmonics order, 1 to 3 (default 3)")
    ->transform(Integer(1, 3, "1, 2 or 3"))
    ->type_name("N");
  view
    ->add_option_function<std::string>(
      "--sh-evaluation", [&o](const std::string& where) { o.PerFragment = where == "fragment"; },
      "where sh media are evaluated toward the eye: once per\n"
      "view and voxel (default; cheapest under Mesa), or per\n"
      "fragment in the slice shader (no work on a view change)")
    ->transform(OneOf({ "voxel", "fragment" }))
    ->type_name("voxel|fragment");
  view
    ->add_option("--keys", o.Keys,
      "keys pressed at the start (p, d, m; and s with\n"
      "--exit-after), e.g. --keys pp")
    ->type_name("KEYS");
  CLI::Option* exitAfter = view->add_option("--exit-after", o.ExitAfter,
    "interactive window driven by a timer: press the --keys,\n"
    "turn the camera 5 degrees a frame for N frames, quit\n"
    "and print the work done (a test of the interactive path)");
  exitAfter->transform(Integer(1, 100000, "a number of frames in [1, 100000]"))->type_name("N");
  view->add_flag_callback(
    "--no-overlay", [&o]() { o.Overlay = false; }, "hide the text overlay");
  view
    ->add_option("--moving-sample-distance", o.MovingSampleDistance,
      "while the camera moves (and during --orbit), draw the\n"
      "media D times coarser along each axis, then upsample\n"
      "them (1 to 16; default 2; 1: full resolution); at\n"
      "rest they are drawn at full resolution")
    ->transform(Number(1.0, 16.0, "a number in [1, 16]"))
    ->type_name("D");
  CLI::Option* orbit = view->add_option("--orbit", o.Orbit,
    "render N frames around the focal point (off screen, no\n"
    "window interaction; X or EGL) and print\n"
    "the median and 95th percentile of the update and\n"
    "render times, and the textures recomputed meanwhile");
  orbit->transform(Integer(1, 100000, "a number of frames in [1, 100000]"))->type_name("N");
  exitAfter->excludes(orbit);
  view->add_option("--frames-out", o.FramesOut, "with --orbit: write DIR/frame_NNNN.png")
    ->transform(NotEmpty("a path"))
    ->type_name("DIR")
    ->needs(orbit);
  view->add_option("--csv", o.Csv, "with --orbit: per-frame times (frame,update_ms,render_ms)")
    ->transform(NotEmpty("a path"))
    ->type_name("FILE")
    ->needs(orbit);
  view->footer("Keys: p  more particles (doubles the count; the new particles are added to\n"
               "         the existing histograms)\n"
               "      d  switch the media between per-view textures and spherical harmonics\n"
               "      m  show or hide the media\n"
               "      s  save the window to brume-view-NNNN.png\n"
               "      n  next time step, b  previous (a scene that changes over time)\n"
               "      q  quit");
  // After the options and their --orbit checks: which keys depends on --exit-after.
  view->final_callback(
    [&o]()
    {
      const std::string why = CheckKeys(o.Keys, o.ExitAfter > 0);
      if (!why.empty())
      {
        throw CLI::ValidationError(why);
      }
    });
}

const char* const SlabUsage =
  "brume validate slab --albedo A --optical-thickness B --g G [--particles N] [--seed S]";

void AddValidate(CLI::App& app, SlabOptions& o, const Defaults& d)
{
  CLI::App* validate = AddCommand(app, "validate", SlabUsage,
    "Checks the particle tracer against published values; the experiment: slab.");
  validate->require_subcommand(0, 1);
  CLI::App* slab = AddCommand(*validate, "slab", SlabUsage,
    "Traces a collimated beam at normal incidence onto a laterally infinite,\n"
    "index-matched slab (sigma_t = 1, thickness B, albedo A, Henyey-Greenstein\n"
    "g = G) and prints a CSV header and the fractions of the incident power\n"
    "reflected after scattering, transmitted after scattering and transmitted\n"
    "unscattered, each with its Monte Carlo standard error.");
  validate->final_callback(
    [slab]()
    {
      if (!*slab)
      {
        throw CLI::RequiredError(
          "validate needs an experiment: slab", CLI::ExitCodes::RequiredError);
      }
    });
  slab->add_option("--albedo", o.Albedo, "single-scattering albedo, in [0, 1]")
    ->transform(Number(0.0, 1.0, "a number in [0, 1]"))
    ->type_name("A")
    ->required();
  slab->add_option("--optical-thickness", o.OpticalThickness, "optical thickness, in (0, 1e4]")
    ->transform(Number(1e-9, 1e4, "a number in (0, 1e4]"))
    ->type_name("B")
    ->required();
  slab->add_option("--g", o.G, "Henyey-Greenstein asymmetry, in (-1, 1)")
    ->transform(Number(-0.999999, 0.999999, "a number in (-1, 1)"))
    ->type_name("G")
    ->required();
  slab->add_option("--particles", o.Particles, "particles traced (default 1000000, at least 2)")
    ->transform(Integer(
      2, 10000000000LL, "an integer in [2, 1e10] (a standard error needs at least 2 particles)"))
    ->type_name("N");
  AddSeed(slab, o.Seed, d);
}

void AddBench(CLI::App& app, BenchOptions& o, const Defaults& d)
{
  CLI::App* bench = AddCommand(app, "bench", "brume bench [--particles N] [--seed S] [--json FILE]",
    "Traces the built-in scene and casts the same rays through Embree alone;\n"
    "prints particles/s, hits/s, the ratio of the ray throughputs and the peak\n"
    "memory per stored hit; then the reconstruction's full and per-view times\n"
    "and, with a display, frame times against vtkGPUVolumeRayCastMapper; last,\n"
    "every figure beside its target.");
  bench
    ->add_option_function<long long>(
      "--particles", [&o](const long long& n) { o.Particles = n; },
      "particles traced (default " + Text(d.Particles) + ")")
    ->transform(Integer(1, 10000000000LL, "an integer in [1, 1e10]"))
    ->type_name("N");
  AddSeed(bench, o.Seed, d);
  bench->add_option("--json", o.Json, "also write the figures, targets and verdicts as JSON")
    ->transform(NotEmpty("a file name"))
    ->type_name("FILE");
  bench
    ->add_option("--volume-size", o.VolumePoints,
      "points along each axis of the render pass's Wavelet\n"
      "volume, whose transfer-function edits are timed\n"
      "(default 21; 512: a scientific volume's, which the\n"
      "edits' targets are for)")
    ->transform(Integer(2, 1024, "an integer in [2, 1024]"))
    ->type_name("N");
}

void AddChart(CLI::App& app, ChartOptions& o, const Defaults& d)
{
  CLI::App* chart =
    AddCommand(app, "chart", "brume chart [SCENE] [-o chart.png] [--csv chart.csv] [options]",
      "Renders a scene (default: the built-in one) with the three-phase pipeline\n"
      "at a ladder of particle budgets (media per view, as in the paper, and as\n"
      "spherical harmonics) and with the path tracer at a ladder of samples per\n"
      "pixel, measures each image's error against a converged reference (cached\n"
      "on disk) and draws error against time, log-log, with VTK's charts, off\n"
      "screen (X, or EGL without a display).");
  chart->add_option("SCENE", o.Scene, "a scene file (default: the built-in scene)");
  chart->add_option("-o,--output", o.Output, "the chart (PNG, default chart.png)")
    ->transform(NotEmpty("a file name"))
    ->type_name("FILE");
  chart
    ->add_option("--csv", o.Csv,
      "the measurements (default chart.csv): method (pipeline,\n"
      "pipeline-new-view, pipeline-sh, pipeline-sh-new-view,\n"
      "path-tracer), budget, seconds, rel_mae, rel_rmse,\n"
      "rel_mae_medium, rel_rmse_medium")
    ->transform(NotEmpty("a file name"))
    ->type_name("FILE");
  chart
    ->add_option_function<std::string>(
      "--size", [&o](const std::string& size) { ParseSize(size, 4096, o.Width, o.Height); },
      "image size (default 128x128)")
    ->transform(Size(4096))
    ->type_name("WxH");
  chart
    ->add_option_function<std::string>(
      "--particles",
      [&o](const std::string& range)
      { ParseRange(range, 1, 10000000000LL, o.MinParticles, o.MaxParticles); },
      "the pipeline's ladder, by powers of 10 (default\n10000:10000000)")
    ->transform(Range(1, 10000000000LL, "MIN:MAX with 1 <= MIN <= MAX <= 1e10"))
    ->type_name("MIN:MAX");
  chart
    ->add_option(
      "--max-spp", o.MaxSamples, "the path tracer's ladder, by powers of 4 (default 1024)")
    ->transform(Integer(1, 1000000, "an integer in [1, 1e6]"))
    ->type_name("N");
  chart
    ->add_option("--supersample", o.Supersample,
      "the pipeline's K x K samples of each pixel's area (K^2\n"
      "frames on a rotated grid, default 4; 8 places an\n"
      "emitter's edges four times as closely), in the sweep too")
    ->transform(Integer(1, 16, "an integer in [1, 16]"))
    ->type_name("K");
  chart
    ->add_option(
      "--sh-order", o.ShOrder, "order of the spherical-harmonics rows, 1 to 3 (default 3)")
    ->transform(Integer(1, 3, "1, 2 or 3"))
    ->type_name("N");
  chart
    ->add_option_function<double>(
      "--threshold", [&o](const double& threshold) { o.Threshold = threshold; },
      "the pipeline's radiosity threshold, in particles\n"
      "(default: the scene file's, else " +
        Text(d.Threshold) + ")")
    ->transform(Number(1e-6, 1e12, "a positive number"))
    ->type_name("T");
  chart
    ->add_option("--reference-spp", o.ReferenceSamples,
      "samples per pixel of the converged reference (default 16384)")
    ->transform(Integer(1, 1000000, "an integer in [1, 1e6]"))
    ->type_name("N");
  chart
    ->add_option("--cache", o.CacheDirectory,
      "where converged references are kept (default\n"
      "$XDG_CACHE_HOME/brume or ~/.cache/brume)")
    ->transform(NotEmpty("a directory"))
    ->type_name("DIR");
  chart->add_flag("--sweep", o.Sweep,
    "the stability sweep instead: g, optical thickness,\n"
    "albedo, a thin sheet (1, 2, 4 voxels), particle count\n"
    "(up to the --particles maximum),\n"
    "glossy (exponents 50 and 1000) and mirror floor, one at\n"
    "a time; per case the\n"
    "pipeline's error and the path tracer's at the same time\n"
    "(CSV: parameter, value, pipeline_seconds,\n"
    "pipeline_rel_mae, pathtracer_spp, pathtracer_seconds,\n"
    "pathtracer_rel_mae, finite, pipeline_sh_rel_mae, the\n"
    "block errors, reference_noise: what an image equal to\n"
    "the truth would score against the reference)");
  chart
    ->add_option(
      "--medium", o.Medium, "the medium the sweep edits (default: the scene's\nfirst medium)")
    ->transform(NotEmpty("a medium's name"))
    ->type_name("NAME");
  chart
    ->add_option("--surface", o.Surface,
      "the surface the sweep makes glossy and mirror, and\n"
      "the medium reaches through (default: chosen\n"
      "automatically)")
    ->transform(NotEmpty("a surface's name"))
    ->type_name("NAME");
  chart
    ->add_option("--parameter", o.Parameter,
      "the sweep runs only this parameter's cases: g, optical\n"
      "thickness, albedo, sheet voxels, particles, the\n"
      "surface's name, or surface in medium")
    ->transform(NotEmpty("a parameter's name"))
    ->type_name("NAME");
}

std::string DefaultCacheDirectory()
{
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  return xdg && *xdg ? std::string(xdg) + "/brume"
                     : std::string(home ? home : ".") + "/.cache/brume";
}

// "brume render" for the render command.
std::string CommandPath(const CLI::App* command)
{
  const CLI::App* parent = command->get_parent();
  return parent ? CommandPath(parent) + " " + command->get_name() : command->get_name();
}

int UsageError(const CLI::App& app, const std::string& message, std::ostream& err)
{
  // The innermost command reached: its usage.
  const CLI::App* command = &app;
  while (!command->get_subcommands().empty())
  {
    command = command->get_subcommands().front();
  }
  const std::string path = command == &app ? "brume COMMAND" : CommandPath(command);
  err << "brume: " << message << "\n"
      << std::static_pointer_cast<BrumeFormatter>(command->get_formatter())->make_usage(command, "")
      << "'" << path << " --help' "
      << (command == &app ? "describes a command" : "lists the options") << ".\n";
  return 2;
}
}

int ParseCommandLine(
  int argc, char** argv, BrumeCommandLine& line, std::ostream& out, std::ostream& err)
{
  CLI::App app("Renders scenes with participating media in the three phases of Jimenez &\n"
               "Pueyo (2003): particle tracing, radiance reconstruction, slice rendering.\n"
               "'brume COMMAND --help' describes a command.",
    "brume");
  app.formatter(std::make_shared<BrumeFormatter>(
    "brume render [SCENE] -o OUTPUT [options]\n"
    "       brume view [SCENE] [options]\n"
    "       brume validate slab --albedo A --optical-thickness B --g G [options]\n"
    "       brume bench [--particles N] [--seed S] [--json FILE]\n"
    "       brume chart [SCENE] [-o chart.png] [--csv chart.csv] [options]\n"
    "       brume --version"));
  app.set_help_flag("-h,--help", "print this help");
  app.add_flag("--version", "print the versions of brume and VTK");
  app.require_subcommand(1);
  // As before CLI11: an option given twice takes its last value.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);

  line = BrumeCommandLine();
  line.Chart.CacheDirectory = DefaultCacheDirectory();
  const Defaults defaults = ReadDefaults();
  AddRender(app, line.Render, defaults);
  AddView(app, line.View, defaults);
  AddValidate(app, line.Slab, defaults);
  AddBench(app, line.Bench, defaults);
  AddChart(app, line.Chart, defaults);
  for (const char* name : { "render", "view", "bench", "chart" })
  {
    app.get_subcommand(name)
      ->add_option("--window", line.Window,
        "the render window: x, egl, osmesa or auto (default:\n"
        "BRUME_RENDER_WINDOW, else X with a DISPLAY, else EGL)")
      ->transform(OneOf({ "auto", "x", "egl", "osmesa" }))
      ->type_name("KIND");
    app.get_subcommand(name)
      ->add_option_function<long long>(
        "--threads", [&line](const long long& n) { line.Threads = static_cast<int>(n); },
        "threads of every phase (default: VTK_SMP_MAX_THREADS, else\n"
        "every core); the images do not depend on it")
      ->transform(Integer(1, 4096, "an integer in [1, 4096]"))
      ->type_name("N");
  }

  // Help and version as the first argument, and a command's help wherever
  // -h or --help is among its arguments (whatever else they hold).
  const std::string first = argc > 1 ? argv[1] : "";
  if (first == "-h" || first == "--help" || first == "help")
  {
    out << app.help();
    return 0;
  }
  if (first == "--version" || first == "version")
  {
    line.Run = BrumeCommandLine::Command::Version;
    return -1;
  }
  if (argc < 2)
  {
    return UsageError(app, "missing command", err);
  }
  const std::vector<CLI::App*> named =
    app.get_subcommands([&first](CLI::App* command) { return command->get_name() == first; });
  if (named.empty())
  {
    return UsageError(app, "unknown command '" + first + "'", err);
  }
  for (int i = 2; i < argc; ++i)
  {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help")
    {
      out << (first == "validate" ? named[0]->get_subcommand("slab") : named[0])->help();
      return 0;
    }
  }

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return UsageError(app, e.what(), err);
  }
  using Command = BrumeCommandLine::Command;
  line.Run = *app.get_subcommand("render") ? Command::Render
    : *app.get_subcommand("view")          ? Command::View
    : *app.get_subcommand("validate")      ? Command::ValidateSlab
    : *app.get_subcommand("bench")         ? Command::Bench
                                           : Command::Chart;
  return -1;
}
