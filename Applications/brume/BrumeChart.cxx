// SPDX-License-Identifier: BSD-3-Clause
// `brume chart`: error against time (vtkBrumeErrorChart) and the stability
// sweep (vtkBrumeStabilitySweep) of Brume::Evaluation, on the built-in scene
// or a scene file: options in, tables and charts out, an exit code.
#include "BrumeCommands.h"
#include "BrumeRender.h"

#include "vtkAlgorithmOutput.h"
#include "vtkBrumeErrorChart.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeReferenceCache.h"
#include "vtkBrumeStabilitySweep.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>

namespace
{
// How the scene is named in the chart's title and in the reference cache.
struct SceneNames
{
  std::string Name, CacheKey;
};

// The built-in scene keeps its names (its references stay valid); a scene
// file is named by its file name, and its references by its stem and a
// digest (FNV-1a) of its bytes, so that an edited file gets new ones.
SceneNames NamesOf(const std::string& scene)
{
  if (scene.empty() || scene == "default")
  {
    return { "default scene", "default-scene" };
  }
  std::ifstream in(scene, std::ios::binary);
  std::uint64_t digest = 14695981039346656037ull;
  for (std::istreambuf_iterator<char> c(in), end; c != end; ++c)
  {
    digest = (digest ^ static_cast<unsigned char>(*c)) * 1099511628211ull;
  }
  std::ostringstream key;
  key << std::filesystem::path(scene).stem().string() << "-" << std::hex << std::setw(16)
      << std::setfill('0') << digest;
  return { std::filesystem::path(scene).filename().string(), key.str() };
}

double Value(vtkTable* table, const char* column, vtkIdType row)
{
  return vtkArrayDownCast<vtkDataArray>(table->GetColumnByName(column))->GetTuple1(row);
}

// Prints the chart's rows as they are measured (on its progress events),
// after where its converged reference came from.
struct ChartPrinter
{
  vtkBrumeErrorChart* Chart;
  vtkIdType Printed = 0;

  void Print()
  {
    vtkTable* t = this->Chart->GetOutput();
    if (this->Printed == 0 && t->GetNumberOfRows() > 0)
    {
      vtkBrumeReferenceCache* reference = this->Chart->GetReferenceCache();
      const std::filesystem::path cached = reference->GetFileName();
      if (reference->GetReadFromCache())
      {
        std::cerr << "brume: converged reference read from " << cached << "\n";
      }
      else
      {
        std::cerr << "brume: converged reference (" << reference->GetSamplesPerPixel()
                  << " spp) in " << reference->GetRenderSeconds() << " s, cached in " << cached
                  << "\n";
      }
    }
    auto* method = vtkStringArray::SafeDownCast(t->GetColumnByName("method"));
    for (; this->Printed < t->GetNumberOfRows(); ++this->Printed)
    {
      const vtkIdType r = this->Printed;
      std::printf("%-22s %12.0f %9.3f s  rel. MAE %.4f  RMSE %.4f  (medium %.4f, %.4f)\n",
        method->GetValue(r).c_str(), Value(t, "budget", r), Value(t, "seconds", r),
        Value(t, "rel_mae", r), Value(t, "rel_rmse", r), Value(t, "rel_mae_medium", r),
        Value(t, "rel_rmse_medium", r));
    }
    std::fflush(stdout);
  }
};

// Prints the sweep's rows as a Markdown table, as they are measured.
struct SweepPrinter
{
  vtkBrumeStabilitySweep* Sweep;
  vtkIdType Printed = 0;

  void Print()
  {
    vtkTable* t = this->Sweep->GetOutput();
    auto* parameter = vtkStringArray::SafeDownCast(t->GetColumnByName("parameter"));
    auto* value = vtkStringArray::SafeDownCast(t->GetColumnByName("value"));
    for (; this->Printed < t->GetNumberOfRows(); ++this->Printed)
    {
      const vtkIdType r = this->Printed;
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %.2f | %.3f |\n",
        parameter->GetValue(r).c_str(), value->GetValue(r).c_str(), Value(t, "pipeline_rel_mae", r),
        Value(t, "pipeline_sh_rel_mae", r), Value(t, "pathtracer_rel_mae", r),
        Value(t, "pipeline_seconds", r), Value(t, "reference_noise", r));
    }
    std::fflush(stdout);
  }
};

// Says which objects the sweep edits, and which cases the scene skips.
bool ReportSweepObjects(vtkBrumeStabilitySweep* sweep, vtkDataObject* scene)
{
  const char* medium = sweep->ChooseMedium(scene);
  const char* surface = medium ? sweep->ChooseSurface(scene) : nullptr;
  if (!medium || !surface)
  {
    return false;
  }
  std::cerr << "brume: the sweep edits the medium '" << medium << "' and the surface '" << surface
            << "'\n";
  if (!*medium)
  {
    std::printf("The scene has no medium: the g, optical thickness, albedo, sheet and "
                "surface-in-medium cases are skipped.\n\n");
  }
  if (!*surface)
  {
    std::printf("The scene has no (non-emissive) surface: the glossy, mirror and "
                "surface-in-medium cases are skipped.\n\n");
  }
  return true;
}

// Where methods are known to fail: one parameter at a time, the pipeline
// against the path tracer given the same time, both against a converged
// reference.
int RunSweep(const ChartOptions& options, vtkAlgorithm* scene, const SceneNames& names)
{
  vtkNew<vtkBrumeStabilitySweep> sweep;
  sweep->SetInputConnection(scene->GetOutputPort());
  sweep->SetSize(options.Width, options.Height);
  sweep->SetMinParticles(options.MinParticles);
  sweep->SetMaxParticles(options.MaxParticles);
  sweep->SetReferenceSamples(options.ReferenceSamples);
  sweep->SetRadiosityThreshold(*options.Threshold);
  sweep->SetSeed(static_cast<vtkIdType>(options.Seed));
  sweep->SetDirectionalOrder(options.ShOrder);
  sweep->SetSupersampling(options.Supersample);
  sweep->SetCacheDirectory(options.CacheDirectory.c_str());
  sweep->SetSceneName(names.Name.c_str());
  sweep->SetCacheKey(names.CacheKey.c_str());
  sweep->SetMediumName(options.Medium.c_str());
  sweep->SetParameter(options.Parameter.c_str());
  // The built-in scene keeps the documented sweep (Data/doc/sweep-default-scene.csv):
  // its floor, where the automatic choice would take the back wall.
  const bool builtIn = options.Scene.empty() || options.Scene == "default";
  sweep->SetSurfaceName(options.Surface.empty() && builtIn ? "floor" : options.Surface.c_str());
  if (!ReportSweepObjects(sweep, scene->GetOutputDataObject(0)))
  {
    return 1;
  }
  if (!std::ofstream(options.Csv))
  {
    std::cerr << "brume: cannot write " << options.Csv << "\n";
    return 1;
  }
  std::printf("| parameter | value | pipeline rel. MAE | SH media rel. MAE | path tracer rel. MAE "
              "(same time) | time (s) | reference's own noise |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
  SweepPrinter printer{ sweep };
  sweep->AddObserver(vtkCommand::ProgressEvent, &printer, &SweepPrinter::Print);
  if (!sweep->GetExecutive()->Update())
  {
    std::cerr << "brume: the sweep failed (see the error above).\n";
    std::remove(options.Csv.c_str()); // made empty by the check above: no partial output
    return 1;
  }
  if (!sweep->WriteCsv(options.Csv.c_str()))
  {
    return 1;
  }
  if (!sweep->WriteImage(options.Output.c_str()))
  {
    std::cerr << "brume: could not write " << options.Output << "\n";
    return 1;
  }
  if (!sweep->GetAllFinite())
  {
    std::cerr << "brume: non-finite radiance in the sweep (see the 'finite' column)\n";
    return 1;
  }
  return 0;
}

// The pipeline's particle ladder and the path tracer's sample ladder against
// a converged reference.
int RunErrorChart(const ChartOptions& options, vtkAlgorithm* scene, const SceneNames& names)
{
  vtkNew<vtkBrumeErrorChart> chart;
  chart->SetInputConnection(scene->GetOutputPort());
  chart->SetSize(options.Width, options.Height);
  chart->SetMinParticles(options.MinParticles);
  chart->SetMaxParticles(options.MaxParticles);
  chart->SetMaxSamples(options.MaxSamples);
  chart->SetReferenceSamples(options.ReferenceSamples);
  chart->SetRadiosityThreshold(*options.Threshold);
  chart->SetSeed(static_cast<vtkIdType>(options.Seed));
  chart->SetDirectionalOrder(options.ShOrder);
  chart->SetSupersampling(options.Supersample);
  chart->SetCacheDirectory(options.CacheDirectory.c_str());
  chart->SetSceneName(names.Name.c_str());
  chart->SetCacheKey(names.CacheKey.c_str());
  if (!std::ofstream(options.Csv))
  {
    std::cerr << "brume: cannot write " << options.Csv << "\n";
    return 1;
  }
  ChartPrinter printer{ chart };
  chart->AddObserver(vtkCommand::ProgressEvent, &printer, &ChartPrinter::Print);
  if (!chart->GetExecutive()->Update())
  {
    std::cerr << "brume: the chart failed (see the error above).\n";
    std::remove(options.Csv.c_str()); // made empty by the check above: no partial output
    return 1;
  }
  if (!chart->WriteCsv(options.Csv.c_str()))
  {
    return 1;
  }
  if (!chart->WriteImage(options.Output.c_str()))
  {
    std::cerr << "brume: could not write " << options.Output << "\n";
    return 1;
  }
  return 0;
}
}

int RunChart(const ChartOptions& given)
{
  ChartOptions options = given;
  if (!HasDisplay("chart (it renders with OpenGL)"))
  {
    return 1;
  }
  RenderOptions sceneOptions;
  sceneOptions.Scene = options.Scene;
  vtkNew<vtkBrumePipeline> pipeline;
  if (!ConfigurePipeline(pipeline, sceneOptions))
  {
    return 1;
  }
  vtkAlgorithm* scene = pipeline->GetInputConnection()->GetProducer();
  if (!options.Threshold)
  {
    // The scene file's, else the reconstruction's default.
    options.Threshold = pipeline->GetReconstruction()->GetRadiosityThreshold();
  }
  const SceneNames names = NamesOf(options.Scene);
  return options.Sweep ? RunSweep(options, scene, names) : RunErrorChart(options, scene, names);
}
