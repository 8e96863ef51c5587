// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeCommands.h"

#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include "brume/LightTracer.h"

#include "vtkAlgorithmOutput.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>

#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A field of /proc/self/status in kB (VmRSS, VmHWM), or -1.
long long StatusKiB(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, field.size() + 1, field + ":") == 0)
    {
      return std::stoll(line.substr(field.size() + 1));
    }
  }
  return -1;
}

// Resets the peak resident size (Linux >= 4.0); false when unsupported.
bool ResetPeakMemory()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  return static_cast<bool>(clear);
}

/// One measured figure, with the target it is held to (issue tracker's
/// figures) or the limit it is compared with.
struct Figure
{
  std::string Key;
  double Value;
  std::string Unit;
  std::string Target; // "<= 0.30", ">= 0.4" or empty
  std::string Note;
};

class Report
{
public:
  /// The targets hold for the default budget only.
  explicit Report(bool targetsApply)
    : TargetsApply(targetsApply)
  {
  }
  void Add(
    std::string key, double value, std::string unit, std::string target = {}, std::string note = {})
  {
    this->Figures.push_back(
      { std::move(key), value, std::move(unit), std::move(target), std::move(note) });
  }
  // Met, missed, or "" without a target (or at another budget).
  const char* Verdict(const Figure& f) const
  {
    if (!this->TargetsApply || f.Target.size() < 4)
    {
      return "";
    }
    const double bound = std::stod(f.Target.substr(3));
    const bool met = f.Target[0] == '<' ? f.Value <= bound : f.Value >= bound;
    return met ? "met" : "missed";
  }
  void PrintSummary() const
  {
    std::printf("\n%-33s %12s %-10s %-10s %s\n", "figure", "value", "unit", "target",
      this->TargetsApply ? "" : "(targets hold at 1000000 particles)");
    for (const Figure& f : this->Figures)
    {
      std::printf("%-33s %12.4g %-10s %-10s %s\n", f.Key.c_str(), f.Value, f.Unit.c_str(),
        f.Target.c_str(), Verdict(f));
    }
  }
  // The figures as JSON; false (and a message) when the file cannot be written.
  bool WriteJson(const std::string& path, const nlohmann::json& run) const
  {
    nlohmann::json doc = run;
    doc["figures"] = nlohmann::json::array();
    for (const Figure& f : this->Figures)
    {
      nlohmann::json row = { { "key", f.Key }, { "value", f.Value }, { "unit", f.Unit } };
      if (!f.Target.empty())
      {
        row["target"] = f.Target;
      }
      if (*this->Verdict(f))
      {
        row["met"] = std::string(this->Verdict(f)) == "met";
      }
      if (!f.Note.empty())
      {
        row["note"] = f.Note;
      }
      doc["figures"].push_back(row);
    }
    std::ofstream out(path);
    out << doc.dump(2) << '\n';
    out.close();
    if (!out)
    {
      std::fprintf(stderr, "brume bench: cannot write %s\n", path.c_str());
      return false;
    }
    return true;
  }

private:
  bool TargetsApply;
  std::vector<Figure> Figures;
};
}

namespace
{
// Milliseconds per frame over `frames` renders, the camera turning 0.5
// degrees a frame (the first frame, timed apart in `first` (seconds), uploads
// textures and compiles shaders).
double MillisecondsPerFrame(
  vtkRenderWindow* window, vtkRenderer* renderer, int frames, double* first = nullptr)
{
  auto start = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  if (first)
  {
    *first = Seconds(start);
  }
  start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f)
  {
    renderer->GetActiveCamera()->Azimuth(0.5);
    renderer->ResetCameraClippingRange();
    window->Render();
    window->WaitForCompletion();
  }
  return 1000.0 * Seconds(start) / frames;
}

vtkNew<vtkRenderWindow> MakeWindow(vtkRenderer* renderer)
{
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(512, 512);
  window->AddRenderer(renderer);
  vtkBrumeSceneCamera::SetToDefault(renderer->GetActiveCamera());
  return window;
}

// A full reconstruction of `scene` from the hits, then the update after a 2
// degree turn of the camera, best of 3 (seconds), and the first full one
// in `first` (the process's first: its memory not yet touched); the last
// run's filter.
vtkSmartPointer<vtkBrumeRadianceReconstruction> TimeReconstruction(vtkDataObject* scene,
  vtkAlgorithmOutput* hits, double& full, double& update, double* first = nullptr)
{
  vtkNew<vtkCamera> camera;
  vtkSmartPointer<vtkBrumeRadianceReconstruction> reconstruction;
  for (int run = 0; run < 3; ++run)
  {
    reconstruction = vtkSmartPointer<vtkBrumeRadianceReconstruction>::New();
    reconstruction->SetInputDataObject(0, scene);
    reconstruction->SetInputConnection(1, hits);
    vtkBrumeSceneCamera::SetToDefault(camera);
    reconstruction->SetCamera(camera);
    auto start = std::chrono::steady_clock::now();
    reconstruction->Update();
    full = std::min(full, Seconds(start));
    if (first && run == 0)
    {
      *first = Seconds(start);
    }
    camera->Azimuth(2.0);
    start = std::chrono::steady_clock::now();
    reconstruction->Update();
    update = std::min(update, Seconds(start));
  }
  return reconstruction;
}

// Phase 2: a full reconstruction, then the update after a 2 degree turn of
// the camera (only the anisotropic medium follows the view).
double BenchReconstruction(vtkAlgorithm* source, vtkAlgorithm* tracer, Report& report)
{
  double full = 1e30, update = 1e30, first = 0.0;
  const auto reconstruction = TimeReconstruction(
    source->GetOutputDataObject(0), tracer->GetOutputPort(), full, update, &first);
  const vtkIdType builds = reconstruction->GetNumberOfTextureBuilds();
  const vtkIdType updates = reconstruction->GetNumberOfViewUpdates();
  std::printf("reconstruction     %8.1f ms full (%lld object textures; the paper: 1.14 s), %.1f ms "
              "after a 2 degree turn (%lld view-dependent update), best of 3; the first full "
              "one %.1f ms\n",
    1e3 * full, static_cast<long long>(builds), 1e3 * update, static_cast<long long>(updates),
    1e3 * first);
  report.Add("reconstruction_full", 1e3 * full, "ms", "<= 50", "best of 3; the paper: 1140 ms");
  report.Add("reconstruction_first_call", 1e3 * first, "ms", "<= 50",
    "the process's first, its memory not yet touched");
  report.Add("view_update", 1e3 * update, "ms", "<= 4", "after a 2 degree turn, best of 3");
  return 1e3 * update;
}

// A mirror at display time: the default scene with its floor a mirror
// (rho_s 0.9), the reflection cast from every texel of its 512 x 512
// texture, then again after a 2 degree turn, and a frame with it.
void BenchMirror(
  vtkDataObject* defaultScene, vtkIdType particles, std::uint64_t seed, Report& report)
{
  vtkNew<vtkPartitionedDataSetCollection> scene;
  scene->DeepCopy(defaultScene);
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkInformation* meta = scene->HasMetaData(i) ? scene->GetMetaData(i) : nullptr;
    if (!meta || std::string(meta->Get(vtkCompositeDataSet::NAME())) != "floor")
    {
      continue;
    }
    vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
    vtkNew<vtkStringArray> material;
    material->SetName("BrumeMaterial");
    material->InsertNextValue("mirror");
    fd->RemoveArray("BrumeMaterial");
    fd->AddArray(material);
    const double zero[3] = { 0, 0, 0 }, specular[3] = { 0.9, 0.9, 0.9 };
    fd->RemoveArray("BrumeReflectance");
    fd->RemoveArray("BrumeSpecular");
    vtkBrumeSceneConversion::AppendTuple(fd, "BrumeReflectance", zero, 3);
    vtkBrumeSceneConversion::AppendTuple(fd, "BrumeSpecular", specular, 3);
  }
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(seed);
  tracer->Update();
  double full = 1e30, update = 1e30;
  const auto reconstruction = TimeReconstruction(scene, tracer->GetOutputPort(), full, update);
  std::printf("mirror floor       %8.1f ms full reconstruction, %.1f ms after a 2 degree turn "
              "(the anisotropic medium seen from the eye and from its mirror image, and the "
              "floor's %d x %d texels cast), best of 3\n",
    1e3 * full, 1e3 * update, reconstruction->GetMirrorResolution(),
    reconstruction->GetMirrorResolution());
  report.Add("mirror_reconstruction_full", 1e3 * full, "ms", "", "best of 3");
  report.Add("mirror_view_update", 1e3 * update, "ms", "", "after a 2 degree turn, best of 3");
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    return;
  }
  vtkNew<vtkRenderer> renderer;
  auto window = MakeWindow(renderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(renderer);
  const double frame = MillisecondsPerFrame(window, renderer, 30);
  actors->SetImageSampleDistance(2.0);
  const double moving = MillisecondsPerFrame(window, renderer, 30);
  std::printf("                   %8.2f ms per 512x512 frame with the mirror (%.2f ms with the "
              "media at image sample distance 2)\n",
    frame, moving);
  report.Add("mirror_frame", frame, "ms");
  report.Add("mirror_new_view", 1e3 * update + frame, "ms", "<= 40", "view update plus frame");
  report.Add("mirror_frame_moving", moving, "ms", "", "media at image sample distance 2");
}

// Phase 3: frames of the default scene, and of its medium alone with the
// slice mapper and with vtkGPUVolumeRayCastMapper on the same volume.
void BenchRendering(vtkAlgorithm* source, vtkAlgorithm* tracer, double update, Report& report)
{
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::printf("rendering          skipped: %s\n", vtkBrumeRenderWindowSelection::GetLastError());
    return;
  }
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, source->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->Update();
  const int frames = 30;

  vtkNew<vtkRenderer> sceneRenderer;
  auto sceneWindow = MakeWindow(sceneRenderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(sceneRenderer);
  double firstFrame = 0;
  const double sceneFrame = MillisecondsPerFrame(sceneWindow, sceneRenderer, frames, &firstFrame);
  actors->SetImageSampleDistance(2.0);
  const double movingFrame = MillisecondsPerFrame(sceneWindow, sceneRenderer, frames);
  actors->SetImageSampleDistance(1.0);
  std::printf("rendering          %8.2f ms per 512x512 frame of the default scene (%.2f ms with "
              "the media at image sample distance 2, as while the camera moves)\n",
    sceneFrame, movingFrame);
  report.Add("first_frame", firstFrame, "s", "<= 0.15", "texture upload and shader compilation");
  report.Add("frame", sceneFrame, "ms", "<= 16", "512x512");
  report.Add("frame_moving", movingFrame, "ms", "", "media at image sample distance 2");
  report.Add("new_view", update + sceneFrame, "ms", "<= 25", "view update plus frame");

  // The medium alone.
  vtkImageData* medium = nullptr;
  for (unsigned int i = 0; i < reconstruction->GetOutput()->GetNumberOfPartitionedDataSets(); ++i)
  {
    auto* image = vtkImageData::SafeDownCast(
      reconstruction->GetOutput()->GetPartitionedDataSet(i)->GetPartition(0));
    if (image && image->GetCellData()->GetArray("SourceRadiance"))
    {
      medium = image;
    }
  }
  if (!medium)
  {
    return;
  }
  vtkNew<vtkRenderer> sliceRenderer;
  auto sliceWindow = MakeWindow(sliceRenderer);
  vtkNew<vtkVolume> sliceVolume;
  auto sliceMapper = vtkSmartPointer<vtkBrumeSliceVolumeMapper>::New();
  sliceMapper->SetInputData(medium);
  sliceVolume->SetMapper(sliceMapper);
  sliceVolume->GetProperty()->SetInterpolationTypeToLinear();
  sliceRenderer->AddVolume(sliceVolume);
  const double sliceFrame = MillisecondsPerFrame(sliceWindow, sliceRenderer, frames);

  // The same voxels as RGBA point data (S, sigma_t) for the ray caster,
  // sampled at the same distance as the slices.
  int dims[3];
  medium->GetDimensions(dims);
  vtkNew<vtkImageData> rgba;
  rgba->SetDimensions(dims[0] - 1, dims[1] - 1, dims[2] - 1);
  const double* spacing = medium->GetSpacing();
  const double* origin = medium->GetOrigin();
  rgba->SetSpacing(spacing);
  rgba->SetOrigin(
    origin[0] + spacing[0] / 2, origin[1] + spacing[1] / 2, origin[2] + spacing[2] / 2);
  vtkDataArray* radiance = medium->GetCellData()->GetArray("SourceRadiance");
  vtkDataArray* extinction = medium->GetCellData()->GetArray("Extinction");
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfComponents(4);
  values->SetNumberOfTuples(radiance->GetNumberOfTuples());
  for (vtkIdType i = 0; i < radiance->GetNumberOfTuples(); ++i)
  {
    values->SetTuple4(i, radiance->GetComponent(i, 0), radiance->GetComponent(i, 1),
      radiance->GetComponent(i, 2), extinction->GetComponent(i, 0));
  }
  rgba->GetPointData()->SetScalars(values);
  vtkNew<vtkRenderer> rayRenderer;
  auto rayWindow = MakeWindow(rayRenderer);
  vtkNew<vtkGPUVolumeRayCastMapper> rayMapper;
  rayMapper->SetInputData(rgba);
  rayMapper->AutoAdjustSampleDistancesOff();
  rayMapper->SetSampleDistance(
    static_cast<float>(0.5 * std::min(spacing[0], std::min(spacing[1], spacing[2]))));
  vtkNew<vtkVolume> rayVolume;
  rayVolume->SetMapper(rayMapper);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(4.0, 1.0);
  rayVolume->GetProperty()->SetIndependentComponents(false);
  rayVolume->GetProperty()->SetScalarOpacity(opacity);
  rayVolume->GetProperty()->SetInterpolationTypeToLinear();
  rayVolume->GetProperty()->ShadeOff();
  rayRenderer->AddVolume(rayVolume);
  const double rayFrame = MillisecondsPerFrame(rayWindow, rayRenderer, frames);
  std::printf(
    "medium alone       %8.2f ms per frame with the slice mapper (%d slices), %.2f ms with "
    "vtkGPUVolumeRayCastMapper: ratio %.2f\n",
    sliceFrame, sliceMapper->GetLastNumberOfSlices(), rayFrame, sliceFrame / rayFrame);
  report.Add("medium_slice_mapper", sliceFrame, "ms");
  report.Add("medium_ray_caster", rayFrame, "ms", "", "vtkGPUVolumeRayCastMapper");
  report.Add("slice_over_ray_caster", sliceFrame / rayFrame, "ratio", "<= 1.0");
  // Both at image sample distance 2 (each mapper's own coarser image).
  sliceMapper->SetImageSampleDistance(2.0);
  rayMapper->SetImageSampleDistance(2.0);
  const double sliceCoarse = MillisecondsPerFrame(sliceWindow, sliceRenderer, frames);
  const double rayCoarse = MillisecondsPerFrame(rayWindow, rayRenderer, frames);
  std::printf("  image sample distance 2: %.2f ms with the slice mapper, %.2f ms with "
              "vtkGPUVolumeRayCastMapper: ratio %.2f\n",
    sliceCoarse, rayCoarse, sliceCoarse / rayCoarse);
  report.Add("slice_over_ray_caster_moving", sliceCoarse / rayCoarse, "ratio", "<= 1.0",
    "both at image sample distance 2");
}
}

namespace
{
// The environment of the commands the bench starts: its own, without what
// tells a process that mpirun started it (each command is one process).
std::vector<std::string> ChildEnvironment()
{
  std::vector<std::string> variables;
  for (char** v = environ; *v; ++v)
  {
    const std::string variable = *v;
    bool launcher = false;
    for (const char* prefix : { "OMPI_", "PMI_", "PMIX_", "HYDRA_", "MPIR_" })
    {
      launcher = launcher || variable.compare(0, std::strlen(prefix), prefix) == 0;
    }
    if (!launcher)
    {
      variables.push_back(variable);
    }
  }
  return variables;
}

// One `brume` command (this executable) as a new process, from its start
// to its exit: the wall seconds, or -1 (said) when it fails. With `line`
// not empty, the seconds until it printed a line beginning so instead.
// (posix_spawn rather than vtksys::Process: the child's environment must
// leave out the MPI launcher's variables, which vtksys cannot set.)
double TimeCommand(const std::vector<std::string>& arguments, const std::string& line = {})
{
  // /proc/self/exe itself: the running executable even if its file was
  // replaced by a rebuild meanwhile.
  const char* self = "/proc/self/exe";
  std::vector<std::string> words{ "brume" };
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<std::string> variables = ChildEnvironment();
  // The null-terminated arrays posix_spawn takes, over the strings above.
  auto pointers = [](std::vector<std::string>& strings)
  {
    std::vector<char*> p;
    for (std::string& s : strings)
    {
      p.push_back(s.data());
    }
    p.push_back(nullptr);
    return p;
  };
  std::vector<char*> argv = pointers(words), envp = pointers(variables);
  int out[2];
  if (pipe2(out, O_CLOEXEC) != 0)
  {
    std::perror("brume bench: pipe");
    return -1.0;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO); // clears close-on-exec
  pid_t child = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&child, self, &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (spawned != 0)
  {
    close(out[0]);
    std::fprintf(stderr, "brume bench: cannot start %s: %s\n", self, std::strerror(spawned));
    return -1.0;
  }
  // Its output, line by line (read to the end, so that it never blocks).
  double seconds = -1.0;
  std::string text, pending;
  char buffer[4096];
  for (ssize_t n; (n = read(out[0], buffer, sizeof(buffer))) != 0;)
  {
    if (n < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      break;
    }
    pending.append(buffer, static_cast<std::size_t>(n));
    for (std::size_t end; (end = pending.find('\n')) != std::string::npos;)
    {
      if (!line.empty() && seconds < 0.0 && pending.compare(0, line.size(), line) == 0)
      {
        seconds = Seconds(start);
      }
      text += pending.substr(0, end + 1);
      pending.erase(0, end + 1);
    }
  }
  close(out[0]);
  int status = 0;
  pid_t waited = 0;
  while ((waited = waitpid(child, &status, 0)) < 0 && errno == EINTR)
  {
  }
  if (line.empty())
  {
    seconds = Seconds(start);
  }
  if (waited != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || seconds < 0.0)
  {
    std::fprintf(stderr, "brume bench: 'brume %s' failed%s:\n%s", words[1].c_str(),
      seconds < 0.0 && !line.empty() ? (" before printing '" + line + "'").c_str() : "",
      text.c_str());
    return -1.0;
  }
  return seconds;
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Whole commands as a user runs them, each a new process (start-up, scene,
// tracing, reconstruction, frame): `brume render -o FILE.png` to its exit,
// and `brume view` to its first image on screen; medians of three.
bool BenchWholeCommands(const BenchOptions& options, Report& report)
{
  // Both commands render: skipped, as the frames are, without a window.
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::printf("whole commands     skipped: %s\n", vtkBrumeRenderWindowSelection::GetLastError());
    return true;
  }
  // A directory of its own for the image (mkdtemp: made new, private).
  std::error_code error;
  std::filesystem::path temporary = std::filesystem::temp_directory_path(error);
  if (error)
  {
    temporary = "/tmp";
  }
  std::string name = (temporary / "brume-bench-XXXXXX").string();
  if (!mkdtemp(name.data()))
  {
    std::fprintf(
      stderr, "brume bench: cannot make a directory %s: %s\n", name.c_str(), std::strerror(errno));
    return false;
  }
  const std::filesystem::path directory = name;
  // The same budget, and the window this bench renders in.
  const std::vector<std::string> budget{ "--particles", std::to_string(*options.Particles),
    "--seed", std::to_string(options.Seed), "--window",
    vtkBrumeRenderWindowSelection::GetInstalled() };
  std::vector<std::string> render{ "render", "-o", (directory / "bench.png").string() };
  std::vector<std::string> view{ "view", "--orbit", "1" };
  render.insert(render.end(), budget.begin(), budget.end());
  view.insert(view.end(), budget.begin(), budget.end());
  std::vector<double> renders, views;
  for (int run = 0; run < 3; ++run)
  {
    renders.push_back(TimeCommand(render));
    views.push_back(TimeCommand(view, "first image:"));
    if (renders.back() < 0.0 || views.back() < 0.0)
    {
      std::filesystem::remove_all(directory, error);
      return false;
    }
  }
  std::filesystem::remove_all(directory, error);
  const double whole = Median(renders), first = Median(views);
  std::printf("whole commands     %8.3f s  brume render -o FILE.png, process start to file "
              "written; %.3f s brume view to its first image (medians of 3)\n",
    whole, first);
  report.Add("whole_command", whole, "s", "<= 1.0",
    "brume render -o FILE.png, process start to exit, 512x512, median of 3");
  report.Add("viewer_first_image", first, "s", "",
    "brume view, process start to its first image, 512x512, median of 3");
  return true;
}
}

int RunBench(const BenchOptions& given)
{
  // The budget: the one given, else the light tracer's default (whose
  // figures the targets are stated for).
  const long long defaultParticles = vtkNew<vtkBrumeLightTracer>()->GetNumberOfParticles();
  BenchOptions options = given;
  options.Particles = given.Particles.value_or(defaultParticles);
  const long long particles = *options.Particles;
  Report report(particles == defaultParticles);
  if (!options.Json.empty())
  {
    // Told before the minutes of measuring, not after.
    const auto directory = std::filesystem::absolute(options.Json).parent_path();
    std::error_code error;
    if (!std::filesystem::is_directory(directory, error))
    {
      std::fprintf(stderr, "brume bench: cannot write %s: no directory %s\n", options.Json.c_str(),
        directory.string().c_str());
      return 1;
    }
  }
  std::printf("brume bench: built-in scene, %lld particles, %d threads (vtkSMPTools %s)\n",
    particles, vtkSMPTools::GetEstimatedNumberOfThreads(), vtkSMPTools::GetBackend());

  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();

  // Phase 1 through the VTK filter, hits stored in its output.
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(source->GetOutputPort());
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(options.Seed);
  const long long rssBefore = StatusKiB("VmRSS");
  const bool peakReset = ResetPeakMemory();
  auto start = std::chrono::steady_clock::now();
  tracer->Update();
  const double traceTime = Seconds(start);
  const long long peak = StatusKiB("VmHWM");
  const auto hits = static_cast<double>(tracer->GetOutput()->GetNumberOfPoints());
  const auto rays = static_cast<double>(tracer->GetLastRayCount());
  std::printf(
    "particle tracing   %8.3f s  %7.2f M particles/s  %7.2f M hits/s  (%.0f hits, %.0f rays)\n",
    traceTime, particles / traceTime * 1e-6, hits / traceTime * 1e-6, hits, rays);
  report.Add("particle_tracing", traceTime, "s", "<= 0.30", "hits kept");
  report.Add("hits", hits, "hits");
  if (peakReset && rssBefore > 0 && peak > 0)
  {
    std::printf("peak memory        %8.1f bytes per stored hit (resident-set growth while tracing; "
                "the output arrays take 45)\n",
      1024.0 * static_cast<double>(peak - rssBefore) / hits);
    report.Add("memory_per_hit", 1024.0 * static_cast<double>(peak - rssBefore) / hits, "B",
      "<= 32", "peak resident-set growth while tracing");
  }
  // Tracing again in the same process (another seed, as after an edit in a
  // pipeline): the hits are written where the last output's were, without
  // first touching fresh memory. The bench's own seed is traced once more
  // for the phases after this.
  const auto seed = static_cast<vtkIdType>(options.Seed); // at most 2^63 - 1
  tracer->SetSeed(seed > 0 ? seed - 1 : seed + 1);
  start = std::chrono::steady_clock::now();
  tracer->Update();
  const double againTime = Seconds(start);
  const double reusedMB = static_cast<double>(tracer->GetLastReusedBytes()) / 1e6;
  tracer->SetSeed(options.Seed);
  tracer->Update();
  std::printf("tracing again      %8.3f s  (another seed in the same process: its hits written "
              "where the last run's were, %.0f MB)\n",
    againTime, reusedMB);
  report.Add(
    "particle_tracing_again", againTime, "s", "", "another seed, the last output's memory reused");

  // The same rays, cast alone through Embree.
  brume::Scene scene;
  vtkBrumeSceneConversion::ToScene(source->GetOutput(), scene);
  const brume::RayCaster caster(scene);
  brume::TraceSettings settings;
  settings.Seed = options.Seed;
  const brume::LightTracer core(scene, caster, settings);
  constexpr auto Block = static_cast<long long>(brume::LightTracer::ParticlesPerBlock);
  const long long blocks = (particles + Block - 1) / Block;
  // The same blocks of particles as the filter, hits dropped as they come.
  auto traceBlocks = [&](std::vector<brume::RayLog>* logs)
  {
    vtkSMPTools::For(0, blocks,
      [&](vtkIdType begin, vtkIdType end)
      {
        std::vector<brume::Hit> scratch;
        brume::TraceCounters counters;
        for (vtkIdType b = begin; b < end; ++b)
        {
          core.TraceParticles(static_cast<std::uint64_t>(b * Block),
            static_cast<std::uint64_t>(std::min((b + 1) * Block, particles)),
            static_cast<std::uint64_t>(particles), scratch, counters, logs ? &(*logs)[b] : nullptr,
            false);
        }
      });
  };
  // The transport alone.
  start = std::chrono::steady_clock::now();
  traceBlocks(nullptr);
  const double transportTime = Seconds(start);
  std::printf("transport only     %8.3f s  (same particles, hits not kept: the rest of the tracing "
              "time is storing %.0f hits)\n",
    transportTime, hits);
  report.Add("transport_only", transportTime, "s", "", "the tracing's limit: hits not kept");

  std::vector<brume::RayLog> logs(static_cast<std::size_t>(blocks));
  traceBlocks(&logs);
  std::vector<double> found(static_cast<std::size_t>(blocks), 0.0);
  start = std::chrono::steady_clock::now();
  vtkSMPTools::For(0, blocks,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        const std::vector<float>& r = logs[b].OriginsAndDirections;
        brume::SurfaceHit hit;
        double n = 0;
        for (std::size_t k = 0; k + 5 < r.size(); k += 6)
        {
          n += caster.Intersect({ r[k], r[k + 1], r[k + 2] }, { r[k + 3], r[k + 4], r[k + 5] }, 0.f,
                 std::numeric_limits<float>::infinity(), hit)
            ? 1.0
            : 0.0;
        }
        found[b] = n;
      }
    });
  const double rawTime = Seconds(start);
  double rawRays = 0;
  for (const auto& log : logs)
  {
    rawRays += static_cast<double>(log.OriginsAndDirections.size() / 6);
  }
  std::printf("raw Embree         %8.3f s  %7.2f M rays/s  (the same %.0f rays, closest hit)\n",
    rawTime, rawRays / rawTime * 1e-6, rawRays);
  std::printf("tracer/raw ray throughput ratio: %.3f (tracer %.2f M rays/s)\n",
    (rays / traceTime) / (rawRays / rawTime), rays / traceTime * 1e-6);
  report.Add("raw_embree", rawTime, "s", "", "the same rays, closest hit");
  report.Add(
    "tracer_over_embree_throughput", (rays / traceTime) / (rawRays / rawTime), "ratio", ">= 0.4");
  // What the tracer's ratio would be were storing its hits free.
  const double transportRatio = (rays / transportTime) / (rawRays / rawTime);
  std::printf("transport/raw ray throughput ratio: %.3f (hits not kept: the bound of the tracer's "
              "ratio)\n",
    transportRatio);
  report.Add("transport_over_embree_throughput", transportRatio, "ratio", "",
    "hits not kept: the bound of the tracer's ratio");
  const double update = BenchReconstruction(source, tracer, report);
  BenchRendering(source, tracer, update, report);
  BenchMirror(source->GetOutput(), static_cast<vtkIdType>(particles), options.Seed, report);
  // A command that fails is said, its figures left out, the others kept.
  const bool commands = BenchWholeCommands(options, report);
  report.PrintSummary();
  if (!options.Json.empty())
  {
    const nlohmann::json run = { { "particles", particles }, { "seed", options.Seed },
      { "threads", vtkSMPTools::GetEstimatedNumberOfThreads() },
      { "smp_backend", vtkSMPTools::GetBackend() } };
    return report.WriteJson(options.Json, run) && commands ? 0 : 1;
  }
  return commands ? 0 : 1;
}
