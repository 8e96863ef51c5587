// SPDX-License-Identifier: BSD-3-Clause
// `brume chart`: error against time, the fast pipeline against the unbiased
// reference path tracer, drawn with VTK's charts.
#include "BrumeCommands.h"
#include "BrumeRender.h"

#include "vtkAxis.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeSceneActors.h"
#include "vtkCamera.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkCompositeDataSet.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkTrivialProducer.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include "brume/PathTracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct View
{
  double Position[3] = { 0, 0, 4 };
  double FocalPoint[3] = { 0, 0, 0 };
  double ViewUp[3] = { 0, 1, 0 };
  double ViewAngle = 40;
};

struct Errors
{
  double Mae = 0, Rmse = 0, MaeMedium = 0, RmseMedium = 0;
};

// Relative errors of `image` against `reference` (point arrays `Radiance`),
// over every pixel and over the pixels whose ray crosses a medium.
Errors Compare(vtkImageData* image, vtkImageData* reference, const std::vector<char>& medium)
{
  auto* a = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance"));
  auto* r = vtkFloatArray::SafeDownCast(reference->GetPointData()->GetArray("Radiance"));
  double absAll = 0, sqAll = 0, refAll = 0, absMed = 0, sqMed = 0, refMed = 0;
  long long nAll = 0, nMed = 0;
  for (vtkIdType p = 0; p < r->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = a->GetValue(3 * p + c) - r->GetValue(3 * p + c);
      const double ref = std::abs(r->GetValue(3 * p + c));
      absAll += std::abs(d);
      sqAll += d * d;
      refAll += ref;
      ++nAll;
      if (medium[p])
      {
        absMed += std::abs(d);
        sqMed += d * d;
        refMed += ref;
        ++nMed;
      }
    }
  }
  Errors e;
  e.Mae = absAll / refAll;
  e.Rmse = std::sqrt(sqAll / nAll) / (refAll / nAll);
  e.MaeMedium = refMed > 0 ? absMed / refMed : 0.0;
  e.RmseMedium = refMed > 0 ? std::sqrt(sqMed / nMed) / (refMed / nMed) : 0.0;
  return e;
}

vtkSmartPointer<vtkImageData> Reference(vtkAlgorithm* scene, const View& view, int width,
  int height, int spp, std::uint64_t seed, double& seconds)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(view.Position);
  camera->SetFocalPoint(view.FocalPoint);
  camera->SetViewUp(view.ViewUp);
  camera->SetViewAngle(view.ViewAngle);
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(scene->GetOutputPort());
  reference->SetCamera(camera);
  reference->SetSize(width, height);
  reference->SetSamplesPerPixel(spp);
  reference->SetSeed(seed);
  const auto start = std::chrono::steady_clock::now();
  reference->Update();
  seconds = Seconds(start);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reference->GetOutput());
  return image;
}

// The fast pipeline at one budget: full time (trace, reconstruct, render)
// and the time of a new viewpoint (incremental update and render).
struct PipelineRun
{
  vtkSmartPointer<vtkImageData> Radiance;
  double Full = 0, NewView = 0;
};

// Averages blocks of `factor` x `factor` pixels: the pipeline's frames are
// supersampled to match the reference's pixel-area (box-filtered) radiance.
vtkSmartPointer<vtkImageData> Downsample(vtkImageData* image, int factor)
{
  int dims[3];
  image->GetDimensions(dims);
  const int w = dims[0] / factor, h = dims[1] / factor;
  auto* in = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance"));
  vtkNew<vtkFloatArray> out;
  out->SetName("Radiance");
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i)
          {
            sum += in->GetValue(
              3 * ((static_cast<vtkIdType>(y) * factor + j) * dims[0] + x * factor + i) + c);
          }
        out->SetValue(
          3 * (static_cast<vtkIdType>(y) * w + x) + c, static_cast<float>(sum / (factor * factor)));
      }
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->SetDimensions(w, h, 1);
  result->GetPointData()->SetScalars(out);
  return result;
}

constexpr int Supersampling = 4;

PipelineRun Pipeline(vtkAlgorithm* scene, const View& view, int width, int height,
  long long particles, double threshold, std::uint64_t seed, bool directional = false,
  int order = 3)
{
  PipelineRun run;
  width *= Supersampling;
  height *= Supersampling;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(view.Position);
  camera->SetFocalPoint(view.FocalPoint);
  camera->SetViewUp(view.ViewUp);
  camera->SetViewAngle(view.ViewAngle);
  vtkNew<vtkRenderer> renderer;
  renderer->SetActiveCamera(camera);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);

  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(seed);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, scene->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetCamera(camera);
  reconstruction->SetRadiosityThreshold(threshold);
  reconstruction->SetDirectionalRadiance(directional);
  reconstruction->SetDirectionalOrder(order);
  reconstruction->Update();
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(renderer);
  renderer->ResetCameraClippingRange();
  window->Render();
  window->WaitForCompletion();
  run.Full = Seconds(start);
  run.Radiance = Downsample(capture->Capture(), Supersampling);

  // A new viewpoint: come back to this one from 2 degrees away (drawn
  // there, so that every per-view step runs again).
  camera->Azimuth(-2.0);
  reconstruction->Update();
  actors->UpdateInputs(reconstruction->GetOutput());
  window->Render();
  window->WaitForCompletion();
  camera->Azimuth(2.0);
  const auto viewStart = std::chrono::steady_clock::now();
  reconstruction->Update();
  actors->UpdateInputs(reconstruction->GetOutput());
  window->Render();
  window->WaitForCompletion();
  run.NewView = Seconds(viewStart);
  return run;
}

// Pixels whose ray crosses a medium of the scene.
std::vector<char> MediumMask(vtkAlgorithm* scene, const View& view, int width, int height)
{
  std::vector<char> mask(static_cast<std::size_t>(width) * height, 0);
  scene->Update();
  auto* collection = vtkPartitionedDataSetCollection::SafeDownCast(scene->GetOutputDataObject(0));
  std::vector<brume::Box> boxes;
  for (unsigned int i = 0; i < collection->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (auto* image =
          vtkImageData::SafeDownCast(collection->GetPartitionedDataSet(i)->GetPartition(0)))
    {
      double b[6];
      image->GetBounds(b);
      boxes.push_back(
        { { static_cast<float>(b[0]), static_cast<float>(b[2]), static_cast<float>(b[4]) },
          { static_cast<float>(b[1]), static_cast<float>(b[3]), static_cast<float>(b[5]) } });
    }
  }
  brume::PinholeCamera camera;
  camera.Position = { static_cast<float>(view.Position[0]), static_cast<float>(view.Position[1]),
    static_cast<float>(view.Position[2]) };
  camera.FocalPoint = { static_cast<float>(view.FocalPoint[0]),
    static_cast<float>(view.FocalPoint[1]), static_cast<float>(view.FocalPoint[2]) };
  camera.ViewUp = { static_cast<float>(view.ViewUp[0]), static_cast<float>(view.ViewUp[1]),
    static_cast<float>(view.ViewUp[2]) };
  camera.ViewAngle = static_cast<float>(view.ViewAngle);
  camera.Width = width;
  camera.Height = height;
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      brume::Vec3 o, d;
      camera.Ray(x + 0.5f, y + 0.5f, o, d);
      for (const brume::Box& box : boxes)
      {
        float t0 = 0.f, t1 = 1e30f;
        if (box.Intersect(o, d, t0, t1))
        {
          mask[static_cast<std::size_t>(y) * width + x] = 1;
        }
      }
    }
  }
  return mask;
}

bool DrawChart(const std::map<std::string, std::vector<std::pair<double, double>>>& curves,
  const std::string& fileName,
  const std::string& title = "Brume: relative mean absolute error against time (default scene)",
  const std::string& xTitle = "wall time (s)", bool logX = true)
{
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(800, 600);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(xTitle);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle("relative mean absolute error");
  chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(logX);
  chart->GetAxis(vtkAxis::LEFT)->SetLogScale(true);
  chart->SetShowLegend(true);
  const unsigned char colours[6][3] = { { 31, 119, 180 }, { 255, 127, 14 }, { 44, 160, 44 },
    { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 } };
  int k = 0;
  for (const auto& curve : curves)
  {
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("time");
    y->SetName(curve.first.c_str());
    for (const auto& point : curve.second)
    {
      x->InsertNextValue(point.first);
      y->InsertNextValue(point.second);
    }
    table->AddColumn(x);
    table->AddColumn(y);
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    line->SetColor(colours[k % 6][0], colours[k % 6][1], colours[k % 6][2], 255);
    line->SetWidth(2.0);
    ++k;
  }
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(fileName.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return writer->GetErrorCode() == 0;
}
}

namespace
{
// A converged reference of `scene`, from the cache when it is there.
vtkSmartPointer<vtkImageData> CachedReference(vtkAlgorithm* scene, const View& view, int w, int h,
  int spp, std::uint64_t seed, const std::string& name, const std::string& directory,
  double& seconds)
{
  std::ostringstream key;
  key << name << "-" << w << "x" << h << "-spp" << spp << "-seed" << seed << "-v1";
  std::filesystem::create_directories(directory);
  const std::filesystem::path cached =
    std::filesystem::path(directory) / ("brume-reference-" + key.str() + ".vti");
  seconds = 0;
  if (std::filesystem::exists(cached))
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(cached.string().c_str());
    reader->Update();
    if (reader->GetOutput()->GetPointData()->GetArray("Radiance"))
    {
      auto image = vtkSmartPointer<vtkImageData>::New();
      image->ShallowCopy(reader->GetOutput());
      return image;
    }
  }
  auto image = Reference(scene, view, w, h, spp, seed, seconds);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(cached.string().c_str());
  writer->SetInputData(image);
  writer->SetDataModeToBinary(); // readable despite expat reparse deferral (see README)
  writer->Write();
  return image;
}

bool Finite(vtkImageData* image)
{
  auto* a = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance"));
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    if (!std::isfinite(a->GetValue(i)))
    {
      return false;
    }
  }
  return true;
}

// Sets a field array of the scene object `name`.
void SetField(vtkPartitionedDataSetCollection* scene, const std::string& object, const char* array,
  const std::vector<double>& values)
{
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (object == scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
    {
      vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
      vtkNew<vtkDoubleArray> a;
      a->SetName(array);
      a->SetNumberOfComponents(static_cast<int>(values.size()));
      a->InsertNextTuple(values.data());
      fd->RemoveArray(array);
      fd->AddArray(a);
    }
  }
}

void SetMaterial(
  vtkPartitionedDataSetCollection* scene, const std::string& object, const char* type)
{
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (object == scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
    {
      vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
      vtkNew<vtkStringArray> a;
      a->SetName("BrumeMaterial");
      a->InsertNextValue(type);
      fd->RemoveArray("BrumeMaterial");
      fd->AddArray(a);
    }
  }
}

// Where methods are known to fail: one parameter at a time, the pipeline
// against the path tracer given the same time, both against a converged
// reference.
int RunSweep(const ChartOptions& options)
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  struct Case
  {
    std::string Parameter, Value;
    std::function<void(vtkPartitionedDataSetCollection*)> Edit;
    long long Particles;
  };
  std::vector<Case> cases;
  const long long particles = options.MaxParticles;
  for (double g : { -0.99, -0.5, 0.0, 0.5, 0.9, 0.99 })
  {
    cases.push_back({ "g", std::to_string(g),
      [g](vtkPartitionedDataSetCollection* s) { SetField(s, "fog", "BrumeG", { g }); },
      particles });
  }
  for (double k : { 0.001, 0.1, 1.0, 10.0, 100.0, 1000.0 })
  {
    cases.push_back({ "optical thickness", std::to_string(1.1 * k),
      [k](vtkPartitionedDataSetCollection* s)
      {
        SetField(s, "fog", "BrumeSigmaS", { k, k, k });
        SetField(s, "fog", "BrumeSigmaA", { 0.1 * k, 0.1 * k, 0.1 * k });
      },
      particles });
  }
  for (double a : { 0.0, 0.5, 0.9, 0.99, 1.0 })
  {
    cases.push_back({ "albedo", std::to_string(a),
      [a](vtkPartitionedDataSetCollection* s)
      {
        SetField(s, "fog", "BrumeSigmaS", { 1.1 * a, 1.1 * a, 1.1 * a });
        SetField(s, "fog", "BrumeSigmaA", { 1.1 * (1 - a), 1.1 * (1 - a), 1.1 * (1 - a) });
      },
      particles });
  }
  for (long long n = std::max<long long>(100, options.MinParticles); n <= particles; n *= 10)
  {
    cases.push_back({ "particles", std::to_string(n), [](vtkPartitionedDataSetCollection*) {}, n });
  }
  cases.push_back({ "floor", "glossy",
    [](vtkPartitionedDataSetCollection* s)
    {
      SetMaterial(s, "floor", "phong");
      SetField(s, "floor", "BrumeReflectance", { 0.2, 0.2, 0.2 });
      SetField(s, "floor", "BrumeSpecular", { 0.6, 0.6, 0.6 });
      SetField(s, "floor", "BrumeExponent", { 50 });
    },
    particles });
  cases.push_back({ "floor", "mirror",
    [](vtkPartitionedDataSetCollection* s)
    {
      SetMaterial(s, "floor", "mirror");
      SetField(s, "floor", "BrumeReflectance", { 0, 0, 0 });
      SetField(s, "floor", "BrumeSpecular", { 0.9, 0.9, 0.9 });
    },
    particles });

  std::ofstream csv(options.Csv);
  if (!csv)
  {
    std::cerr << "brume: cannot write " << options.Csv << "\n";
    return 1;
  }
  csv << "parameter,value,pipeline_seconds,pipeline_rel_mae,pathtracer_spp,pathtracer_seconds,"
         "pathtracer_rel_mae,finite,pipeline_sh_rel_mae\n";
  std::printf("| parameter | value | pipeline rel. MAE | SH media rel. MAE | path tracer rel. MAE "
              "(same time) | time (s) |\n");
  std::printf("|---|---|---:|---:|---:|---:|\n");
  const View view;
  const int w = options.Width, h = options.Height;
  std::map<std::string, std::vector<std::pair<double, double>>> curves;
  bool allFinite = true;
  Pipeline(source, view, w, h, 1000, options.Threshold, options.Seed); // OpenGL start-up
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    const Case& k = cases[c];
    auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
    scene->DeepCopy(source->GetOutput());
    k.Edit(scene);
    vtkNew<vtkTrivialProducer> producer;
    producer->SetOutput(scene);
    const std::vector<char> mask = MediumMask(producer, view, w, h);
    double referenceSeconds = 0;
    std::string name = "sweep-" + k.Parameter + "-" + k.Value;
    std::replace(name.begin(), name.end(), ' ', '_');
    auto converged = CachedReference(producer, view, w, h, options.ReferenceSamples,
      options.Seed + 1000003, name, options.CacheDirectory, referenceSeconds);
    const PipelineRun run =
      Pipeline(producer, view, w, h, k.Particles, options.Threshold, options.Seed);
    const Errors pipeline = Compare(run.Radiance, converged, mask);
    // The path tracer given the pipeline's time: its speed from one sample.
    double oneSample = 0;
    Reference(producer, view, w, h, 1, options.Seed, oneSample);
    const int spp = std::max(1, static_cast<int>(run.Full / std::max(oneSample, 1e-6)));
    double ptSeconds = 0;
    auto pt = Reference(producer, view, w, h, spp, options.Seed, ptSeconds);
    const Errors tracer = Compare(pt, converged, mask);
    // The same budget with directional (spherical-harmonics) media.
    const PipelineRun sh =
      Pipeline(producer, view, w, h, k.Particles, options.Threshold, options.Seed, true,
        options.ShOrder);
    const Errors directional = Compare(sh.Radiance, converged, mask);
    const bool finite =
      Finite(run.Radiance) && Finite(sh.Radiance) && Finite(pt) && Finite(converged);
    allFinite = allFinite && finite;
    csv << k.Parameter << "," << k.Value << "," << run.Full << "," << pipeline.Mae << "," << spp
        << "," << ptSeconds << "," << tracer.Mae << "," << (finite ? 1 : 0) << ","
        << directional.Mae << "\n";
    std::printf("| %s | %s | %.3f | %.3f | %.3f | %.2f |\n", k.Parameter.c_str(), k.Value.c_str(),
      pipeline.Mae, directional.Mae, tracer.Mae, run.Full);
    curves["pipeline"].emplace_back(static_cast<double>(c + 1), pipeline.Mae);
    curves["pipeline, SH media"].emplace_back(static_cast<double>(c + 1), directional.Mae);
    curves["path-tracer, same time"].emplace_back(static_cast<double>(c + 1), tracer.Mae);
  }
  csv.close();
  if (!DrawChart(curves, options.Output, "Brume stability sweep: error per case (see the CSV)",
        "case", false))
  {
    std::cerr << "brume: could not write " << options.Output << "\n";
    return 1;
  }
  if (!allFinite)
  {
    std::cerr << "brume: non-finite radiance in the sweep (see the 'finite' column)\n";
    return 1;
  }
  return 0;
}
}

int RunChart(const ChartOptions& options)
{
  if (!HasDisplay("chart (it renders with OpenGL)"))
  {
    return 1;
  }
  if (options.Sweep)
  {
    return RunSweep(options);
  }
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  scene->Update();
  const View view;
  const int w = options.Width, h = options.Height;

  // The converged reference, cached on disk by its settings.
  std::ostringstream key;
  key << "default-scene-" << w << "x" << h << "-spp" << options.ReferenceSamples << "-seed"
      << options.Seed << "-v1";
  std::filesystem::path cache(options.CacheDirectory);
  std::filesystem::create_directories(cache);
  const std::filesystem::path cached = cache / ("brume-reference-" + key.str() + ".vti");
  vtkSmartPointer<vtkImageData> converged;
  if (std::filesystem::exists(cached))
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(cached.string().c_str());
    reader->Update();
    if (reader->GetOutput()->GetPointData()->GetArray("Radiance"))
    {
      converged = reader->GetOutput();
      std::cerr << "brume: converged reference read from " << cached << "\n";
    }
  }
  if (!converged)
  {
    double seconds = 0;
    // Another seed than the ladder's, so that errors are not correlated.
    converged =
      Reference(scene, view, w, h, options.ReferenceSamples, options.Seed + 1000003, seconds);
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(cached.string().c_str());
    writer->SetInputData(converged);
    writer->SetDataModeToBinary(); // readable despite expat reparse deferral (see README)
    writer->Write();
    std::cerr << "brume: converged reference (" << options.ReferenceSamples << " spp) in "
              << seconds << " s, cached in " << cached << "\n";
  }
  const std::vector<char> mask = MediumMask(scene, view, w, h);

  std::ofstream csv(options.Csv);
  if (!csv)
  {
    std::cerr << "brume: cannot write " << options.Csv << "\n";
    return 1;
  }
  csv << "method,budget,seconds,rel_mae,rel_rmse,rel_mae_medium,rel_rmse_medium\n";
  std::map<std::string, std::vector<std::pair<double, double>>> curves;
  auto record = [&](const std::string& method, double budget, double seconds, const Errors& e)
  {
    csv << method << "," << budget << "," << seconds << "," << e.Mae << "," << e.Rmse << ","
        << e.MaeMedium << "," << e.RmseMedium << "\n";
    curves[method].emplace_back(seconds, e.Mae);
    std::printf("%-22s %12.0f %9.3f s  rel. MAE %.4f  RMSE %.4f  (medium %.4f, %.4f)\n",
      method.c_str(), budget, seconds, e.Mae, e.Rmse, e.MaeMedium, e.RmseMedium);
  };
  // One untimed run first: OpenGL start-up and shader compilation are not
  // the pipeline's cost.
  Pipeline(scene, view, w, h, 1000, options.Threshold, options.Seed);
  for (long long particles = options.MinParticles; particles <= options.MaxParticles;
       particles *= 10)
  {
    const PipelineRun run = Pipeline(scene, view, w, h, particles, options.Threshold, options.Seed);
    const Errors e = Compare(run.Radiance, converged, mask);
    record("pipeline", static_cast<double>(particles), run.Full, e);
    record("pipeline-new-view", static_cast<double>(particles), run.NewView, e);
    // Directional media: a new view is a render alone.
    const PipelineRun sh =
      Pipeline(scene, view, w, h, particles, options.Threshold, options.Seed, true, options.ShOrder);
    const Errors d = Compare(sh.Radiance, converged, mask);
    record("pipeline-sh", static_cast<double>(particles), sh.Full, d);
    record("pipeline-sh-new-view", static_cast<double>(particles), sh.NewView, d);
  }
  for (int spp = 1; spp <= options.MaxSamples; spp *= 4)
  {
    double seconds = 0;
    auto image = Reference(scene, view, w, h, spp, options.Seed, seconds);
    record("path-tracer", spp, seconds, Compare(image, converged, mask));
  }
  csv.close();
  if (!DrawChart(curves, options.Output))
  {
    std::cerr << "brume: could not write " << options.Output << "\n";
    return 1;
  }
  return 0;
}
