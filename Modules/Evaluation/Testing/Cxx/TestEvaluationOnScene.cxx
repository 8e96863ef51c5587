// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeErrorChart and vtkBrumeStabilitySweep on a tiny budget, on a scene
// that is not the default one (its own object names and camera).
//   TestEvaluationOnScene chart|sweep OUTPUT_DIR
#include "EvaluationTestScenes.h"

#include "vtkBrumeErrorChart.h"
#include "vtkBrumeReferenceCache.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeStabilitySweep.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
int Failures = 0;

void Expect(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

std::string FirstLine(const std::string& fileName)
{
  std::ifstream in(fileName);
  std::string line;
  std::getline(in, line);
  return line;
}

// Every numeric value of the table is finite.
bool Finite(vtkTable* table)
{
  for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
  {
    auto* column = vtkArrayDownCast<vtkDataArray>(table->GetColumn(c));
    for (vtkIdType r = 0; column && r < column->GetNumberOfTuples(); ++r)
    {
      if (!std::isfinite(column->GetTuple1(r)))
      {
        return false;
      }
    }
  }
  return true;
}

double Value(vtkTable* table, const char* column, vtkIdType row)
{
  return vtkArrayDownCast<vtkDataArray>(table->GetColumnByName(column))->GetTuple1(row);
}

void TestChart(const std::string& directory)
{
  vtkNew<vtkBrumeErrorChart> chart;
  chart->SetInputData(Gallery(true));
  chart->SetSize(16, 16);
  chart->SetMinParticles(2000);
  chart->SetMaxParticles(2000);
  chart->SetMaxSamples(4);
  chart->SetReferenceSamples(8);
  chart->SetCacheDirectory((directory + "/evaluation-cache").c_str());
  chart->SetSceneName("gallery");
  Expect(chart->GetExecutive()->Update() == 1, "the chart runs");
  vtkTable* table = chart->GetOutput();
  // 4 pipeline rows for the one budget, the path tracer at 1 and 4 spp.
  Expect(table->GetNumberOfRows() == 6, "6 rows, not " + std::to_string(table->GetNumberOfRows()));
  Expect(Finite(table), "finite errors and times");
  Expect(Value(table, "rel_mae_medium", 0) > 0, "the mist is in view");
  Expect(Value(table, "rel_mae", 4) > Value(table, "rel_mae", 5), "more samples, less error");
  const double first = Value(table, "rel_mae", 4);
  const std::string csv = directory + "/evaluation-chart.csv";
  Expect(chart->WriteCsv(csv.c_str()), "the CSV is written");
  Expect(FirstLine(csv) ==
      "method,budget,seconds,rel_mae,rel_rmse,rel_mae_medium,rel_rmse_medium,block_error",
    "the CSV's columns");
  Expect(chart->WriteImage((directory + "/evaluation-chart.png").c_str()), "the PNG is written");

  // Again: the reference comes from the cache, and so do the same errors.
  chart->Modified();
  chart->Update();
  Expect(chart->GetReferenceCache()->GetReadFromCache(), "the reference is read from the cache");
  Expect(Value(chart->GetOutput(), "rel_mae", 4) == first, "the same errors from the cache");

  // The pipeline's rows take Supersampling^2 frames a pixel (the same
  // particles, other samples of each pixel's area): their images differ,
  // the path tracer's do not.
  const double fourByFour = Value(chart->GetOutput(), "rel_mae", 0);
  Expect(chart->GetSupersampling() == 4, "4 x 4 frames by default");
  chart->SetSupersampling(1);
  chart->Update();
  Expect(Value(chart->GetOutput(), "rel_mae", 0) != fourByFour,
    "one frame a pixel gives the pipeline's rows other images");
  Expect(Value(chart->GetOutput(), "rel_mae", 4) == first, "and the path tracer's the same");
}

void TestSweep(const std::string& directory, bool medium)
{
  vtkNew<vtkBrumeStabilitySweep> sweep;
  sweep->SetInputData(Gallery(medium));
  sweep->SetSize(16, 16);
  sweep->SetMinParticles(1000);
  sweep->SetMaxParticles(1000);
  sweep->SetReferenceSamples(4);
  sweep->SetCacheDirectory((directory + "/evaluation-cache").c_str());
  sweep->SetSceneName(medium ? "gallery" : "gallery without mist");
  Expect(sweep->GetExecutive()->Update() == 1, "the sweep runs");
  vtkTable* table = sweep->GetOutput();
  const std::string surface = sweep->GetChosenSurfaceName();
  Expect(surface == "stage" || surface == "backdrop", "a surface in view: " + surface);
  Expect(std::string(sweep->GetChosenMediumName()) == (medium ? "mist" : ""), "the medium");
  // 24 medium cases (9 g, 6 optical thickness, 6 albedo, 3 sheets; or
  // none), 1 particles case, 3 surface cases, then, with the mist (which
  // stands on the stage and before the backdrop), 3 cases of the mist
  // reaching through the surface.
  const vtkIdType rows = medium ? 31 : 4;
  Expect(table->GetNumberOfRows() == rows, "rows: " + std::to_string(table->GetNumberOfRows()));
  auto* parameter = vtkStringArray::SafeDownCast(table->GetColumnByName("parameter"));
  const vtkIdType lastSurface = medium ? rows - 4 : rows - 1;
  Expect(parameter && parameter->GetValue(lastSurface) == surface, "the surface cases name it");
  for (vtkIdType r = lastSurface + 1; r < rows; ++r)
  {
    Expect(parameter && parameter->GetValue(r) == "surface in medium",
      "the medium reaching through the surface, case " + std::to_string(r));
  }
  Expect(parameter && parameter->GetValue(0) == (medium ? "g" : "particles"), "the first case");
  Expect(sweep->GetAllFinite() && Finite(table), "finite errors and times");
  const std::string csv = directory + "/evaluation-sweep.csv";
  Expect(sweep->WriteCsv(csv.c_str()), "the CSV is written");
  Expect(FirstLine(csv).rfind("parameter,value,pipeline_seconds,pipeline_rel_mae,pathtracer_spp,"
                              "pathtracer_seconds,pathtracer_rel_mae,finite,pipeline_sh_rel_mae",
           0) == 0,
    "the CSV's columns");
  Expect(sweep->WriteImage((directory + "/evaluation-sweep.png").c_str()), "the PNG is written");
  if (!medium)
  {
    return;
  }
  // The mist reaching through the other surface is another scene: its
  // references are its own, not the first surface's read from the cache.
  sweep->SetSurfaceName(surface == "stage" ? "backdrop" : "stage");
  sweep->SetParameter("surface in medium");
  Expect(sweep->GetExecutive()->Update() == 1, "the surface-in-medium cases alone run");
  int references = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory + "/evaluation-cache"))
  {
    const std::string file = entry.path().filename().string();
    references += file.find("mist_through_") != std::string::npos &&
      file.find("surface_in_medium") != std::string::npos;
  }
  Expect(references == 6,
    "a reference per surface and case: " + std::to_string(references) + " instead of 6");
  sweep->SetSurfaceName(nullptr);
  // One parameter alone, against references of 64 and 256 samples per
  // pixel: the references' own noise halves (their standard errors go as
  // 1/sqrt(spp)) where the samples' variance is well estimated, at
  // g = -0.5, 0 and 0.5. At |g| >= 0.9 rare paths carry much of the
  // variance, which so few samples underestimate (ratios 0.77 here, and
  // above 1 between 16 and 64 samples): the column is then a lower bound.
  Expect(table->GetColumnByName("reference_noise") != nullptr, "the reference_noise column");
  std::vector<std::vector<double>> noise;
  for (int spp : { 64, 256 })
  {
    sweep->SetParameter("g");
    sweep->SetReferenceSamples(spp);
    Expect(sweep->GetExecutive()->Update() == 1, "the sweep of g alone runs");
    table = sweep->GetOutput();
    parameter = vtkStringArray::SafeDownCast(table->GetColumnByName("parameter"));
    auto* column = vtkDoubleArray::SafeDownCast(table->GetColumnByName("reference_noise"));
    Expect(table->GetNumberOfRows() == 9 && parameter && parameter->GetValue(8) == "g" && column,
      "g's nine cases alone: " + std::to_string(table->GetNumberOfRows()));
    noise.emplace_back();
    for (vtkIdType r = 0; column && r < column->GetNumberOfTuples(); ++r)
    {
      noise.back().push_back(column->GetValue(r)); // the next update makes a new table
    }
  }
  for (std::size_t r = 0; r < noise[0].size() && r < noise[1].size(); ++r)
  {
    const double ratio = noise[1][r] / noise[0][r];
    std::printf("g case %d: the reference's noise %.4f at 64 spp, %.4f at 256\n",
      static_cast<int>(r), noise[0][r], noise[1][r]);
    Expect(noise[0][r] > 0.0 && noise[1][r] > 0.0, "the reference's noise is measured");
    if (r >= 1 && r <= 3)
    {
      Expect(ratio > 0.35 && ratio < 0.7,
        "the reference's noise at 256 spp over 64 spp: " + std::to_string(ratio));
    }
  }
  sweep->SetParameter("no such parameter");
  Expect(sweep->GetExecutive()->Update() == 0, "an unknown parameter is an error");
}
}

int TestEvaluationOnScene(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestEvaluationOnScene chart|sweep OUTPUT_DIR\n";
    return EXIT_FAILURE;
  }
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const std::string what = argv[1], directory = argv[2];
  if (what == "chart")
  {
    TestChart(directory);
  }
  else
  {
    TestSweep(directory, true);
    TestSweep(directory, false);
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
