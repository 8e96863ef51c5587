// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeErrorChart.h"

#include "vtkBrumeErrorPlot.h"
#include "vtkBrumeEvaluationTable.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeImageError.h"
#include "vtkBrumeMediumMask.h"
#include "vtkBrumeReferenceCache.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <algorithm>
#include <string>

vtkStandardNewMacro(vtkBrumeErrorChart);

namespace
{
// The reference's seed is apart from the images' so that their errors are
// not correlated.
constexpr vtkIdType ReferenceSeedOffset = 1000003;

// The particles of the untimed first run (OpenGL start-up, shaders).
constexpr vtkTypeInt64 WarmUpParticles = 1000;

// Budgets from `first` to `last`, each `factor` times the one before.
int Steps(vtkTypeInt64 first, vtkTypeInt64 last, int factor)
{
  int n = 0;
  for (vtkTypeInt64 budget = first; budget <= last; budget *= factor)
  {
    ++n;
  }
  return n;
}

struct Errors
{
  double Mae = 0, Rmse = 0, MaeMedium = 0, RmseMedium = 0, Block = 0;
};

// The errors of `image` over every pixel and over the medium's pixels.
bool Measure(vtkImageData* image, vtkImageData* reference, vtkImageData* mask, Errors& e)
{
  vtkNew<vtkBrumeImageError> error;
  if (!error->Compare(image, reference))
  {
    return false;
  }
  e.Mae = error->GetRelativeMAE();
  e.Rmse = error->GetRelativeRMSE();
  e.Block = error->GetBlockError();
  if (!error->Compare(image, reference, mask))
  {
    return false;
  }
  e.MaeMedium = error->GetRelativeMAE();
  e.RmseMedium = error->GetRelativeRMSE();
  return true;
}

// The table's columns, in the CSV's order.
struct Columns
{
  vtkStringArray* Method;
  vtkDoubleArray *Budget, *Seconds, *Mae, *Rmse, *MaeMedium, *RmseMedium, *Block;

  explicit Columns(vtkTable* table)
  {
    using T = vtkBrumeEvaluationTable;
    this->Method = T::AddColumn<vtkStringArray>(table, "method");
    this->Budget = T::AddColumn<vtkDoubleArray>(table, "budget");
    this->Seconds = T::AddColumn<vtkDoubleArray>(table, "seconds");
    this->Mae = T::AddColumn<vtkDoubleArray>(table, "rel_mae");
    this->Rmse = T::AddColumn<vtkDoubleArray>(table, "rel_rmse");
    this->MaeMedium = T::AddColumn<vtkDoubleArray>(table, "rel_mae_medium");
    this->RmseMedium = T::AddColumn<vtkDoubleArray>(table, "rel_rmse_medium");
    this->Block = T::AddColumn<vtkDoubleArray>(table, "block_error");
  }

  void Add(const char* method, double budget, double seconds, const Errors& e)
  {
    this->Budget->InsertNextValue(budget);
    this->Seconds->InsertNextValue(seconds);
    this->Mae->InsertNextValue(e.Mae);
    this->Rmse->InsertNextValue(e.Rmse);
    this->MaeMedium->InsertNextValue(e.MaeMedium);
    this->RmseMedium->InsertNextValue(e.RmseMedium);
    this->Block->InsertNextValue(e.Block);
    // Last: the first column counts the table's rows.
    this->Method->InsertNextValue(method);
  }
};
}

vtkBrumeErrorChart::vtkBrumeErrorChart()
  : ReferenceCache(vtkSmartPointer<vtkBrumeReferenceCache>::New())
{
  this->Size[0] = this->Size[1] = 128;
  this->MinParticles = 10000;
  this->MaxParticles = 10000000;
  this->ReferenceSamples = 16384;
}

vtkBrumeErrorChart::~vtkBrumeErrorChart() {}

vtkBrumeReferenceCache* vtkBrumeErrorChart::GetReferenceCache()
{
  return this->ReferenceCache;
}

bool vtkBrumeErrorChart::CheckSettings()
{
  if (!this->CheckCommonSettings())
  {
    return false;
  }
  if (this->MinParticles < 1 || this->MaxParticles < this->MinParticles)
  {
    vtkErrorMacro("The particle budgets need 1 <= MinParticles <= MaxParticles, not "
      << this->MinParticles << " and " << this->MaxParticles << ".");
    return false;
  }
  if (this->MaxSamples < 1)
  {
    vtkErrorMacro("MaxSamples must be at least 1, not " << this->MaxSamples << ".");
    return false;
  }
  return true;
}

int vtkBrumeErrorChart::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* scene = vtkDataObject::GetData(inputVector[0], 0);
  vtkTable* output = vtkTable::GetData(outputVector, 0);
  if (!this->CheckSettings())
  {
    return 0;
  }
  const vtkSmartPointer<vtkCamera> camera = vtkBrumeEvaluationView::Camera(scene, this->Camera);

  // The converged reference, cached on disk by its settings.
  vtkBrumeReferenceCache* reference = this->ReferenceCache;
  reference->SetInputData(scene);
  reference->SetCamera(camera);
  reference->SetSize(this->Size);
  reference->SetSamplesPerPixel(this->ReferenceSamples);
  reference->SetSeed(this->Seed + ReferenceSeedOffset);
  reference->SetCacheDirectory(this->CacheDirectory);
  reference->SetSceneKey(this->CacheKey && *this->CacheKey ? this->CacheKey : this->SceneName);
  if (!reference->GetExecutive()->Update())
  {
    vtkErrorMacro("No converged reference (see the error above).");
    return 0;
  }
  vtkNew<vtkImageData> converged;
  converged->ShallowCopy(reference->GetOutput());
  vtkNew<vtkBrumeMediumMask> mask;
  mask->SetInputData(scene);
  mask->SetCamera(camera);
  mask->SetSize(this->Size);
  if (!mask->GetExecutive()->Update())
  {
    return 0;
  }

  Columns columns(output);
  const double rows =
    4.0 * Steps(this->MinParticles, this->MaxParticles, 10) + Steps(1, this->MaxSamples, 4);
  auto pipeline = [&](vtkTypeInt64 particles, bool directional)
  {
    auto run = vtkSmartPointer<vtkBrumeTimedPipeline>::New();
    run->SetInputData(scene);
    run->SetCamera(camera);
    run->SetSize(this->Size);
    run->SetNumberOfParticles(particles);
    run->SetRadiosityThreshold(this->RadiosityThreshold);
    run->SetSeed(this->Seed);
    run->SetDirectionalRadiance(directional);
    run->SetDirectionalOrder(this->DirectionalOrder);
    run->SetSupersampling(this->Supersampling);
    return run->GetExecutive()->Update() ? run : nullptr;
  };
  // One untimed run first: OpenGL start-up and shader compilation are not
  // the pipeline's cost.
  if (!pipeline(WarmUpParticles, false))
  {
    return 0;
  }
  Errors e;
  for (vtkTypeInt64 particles = this->MinParticles; particles <= this->MaxParticles;
       particles *= 10)
  {
    const auto budget = static_cast<double>(particles);
    for (const bool directional : { false, true })
    {
      const auto run = pipeline(particles, directional);
      if (!run || !Measure(run->GetOutput(), converged, mask->GetOutput(), e))
      {
        return 0;
      }
      columns.Add(directional ? "pipeline-sh" : "pipeline", budget, run->GetFullSeconds(), e);
      columns.Add(directional ? "pipeline-sh-new-view" : "pipeline-new-view", budget,
        run->GetNewViewSeconds(), e);
      this->UpdateProgress(output->GetNumberOfRows() / rows);
    }
  }
  for (int spp = 1; spp <= this->MaxSamples; spp *= 4)
  {
    vtkNew<vtkBrumeReferenceCache> tracer; // without a cache directory: renders
    tracer->SetInputData(scene);
    tracer->SetCamera(camera);
    tracer->SetSize(this->Size);
    tracer->SetSamplesPerPixel(spp);
    tracer->SetSeed(this->Seed);
    if (!tracer->GetExecutive()->Update() ||
      !Measure(tracer->GetOutput(), converged, mask->GetOutput(), e))
    {
      return 0;
    }
    columns.Add("path-tracer", spp, tracer->GetRenderSeconds(), e);
    this->UpdateProgress(output->GetNumberOfRows() / rows);
  }
  return 1;
}

bool vtkBrumeErrorChart::WriteImage(const char* fileName)
{
  vtkTable* table = this->GetOutput();
  auto* method = vtkStringArray::SafeDownCast(table->GetColumnByName("method"));
  vtkDataArray* seconds = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName("seconds"));
  vtkDataArray* mae = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName("rel_mae"));
  vtkNew<vtkBrumeErrorPlot> plot;
  for (vtkIdType r = 0; method && seconds && mae && r < table->GetNumberOfRows(); ++r)
  {
    plot->AddPoint(method->GetValue(r).c_str(), seconds->GetTuple1(r), mae->GetTuple1(r));
  }
  const std::string title = std::string("Brume: relative mean absolute error against time (") +
    (this->SceneName ? this->SceneName : "") + ")";
  plot->SetTitle(title.c_str());
  plot->SetXTitle("wall time (s)");
  plot->LogXOn();
  if (!plot->Write(fileName))
  {
    vtkErrorMacro("Could not write the chart to " << (fileName ? fileName : "(no file)") << ".");
    return false;
  }
  return true;
}

void vtkBrumeErrorChart::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxSamples: " << this->MaxSamples << "\n";
}
