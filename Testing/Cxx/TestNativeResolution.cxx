// SPDX-License-Identifier: BSD-3-Clause
// A scientific volume keeps its own resolution: a classified field is
// reconstructed and drawn at its own grid where NativeMemoryLimit holds it,
// coarsened with one warning where it does not; the same arrays are
// converted once for the tracer, the reconstruction and the renderer, an
// edit of the transfer function keeps the converted scalars, and what was
// kept goes with the array.
#include "BrumeLitGroundScene.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include "brume/Scene.h"
#include "brume/TransferFunction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

// A wavy scalar on n^3 points over [-0.5, 0.5]^3, classified by an opacity
// function that bends inside its range: a medium of its own resolution. In
// floats, or rounded into `values` (an 8-bit array, say) when given.
vtkSmartPointer<vtkImageData> Field(int n, vtkDataArray* values = nullptr)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetOrigin(-0.5, -0.5, -0.5);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkSmartPointer<vtkDataArray> s = values;
  if (!s)
  {
    s = vtkSmartPointer<vtkFloatArray>::New();
  }
  s->SetName("wave");
  s->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    const double v = 50.0 + 50.0 * std::sin(9.0 * p[0]) * std::cos(7.0 * p[1] + 2.0 * p[2]);
    s->SetTuple1(i, values ? std::round(v) : static_cast<float>(v));
  }
  image->GetPointData()->SetScalars(s);
  vtkFieldData* fd = image->GetFieldData();
  const double sigmaA[3] = { 0.1, 0.1, 0.1 }, sigmaS[3] = { 0.9, 0.9, 0.9 };
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::SigmaA, sigmaA, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::SigmaS, sigmaS, 3);
  vtkNew<vtkDoubleArray> opacity;
  opacity->SetName(vtkBrumeNames::ScalarOpacity);
  opacity->SetNumberOfComponents(2);
  opacity->InsertNextTuple2(20, 0);
  opacity->InsertNextTuple2(60, 0.2);
  opacity->InsertNextTuple2(100, 0.8);
  fd->AddArray(opacity);
  const double unit = 0.1;
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::ScalarOpacityUnitDistance, &unit, 1);
  return image;
}

vtkSmartPointer<vtkPartitionedDataSetCollection> Scene(vtkImageData* medium)
{
  return BrumeLitGroundScene(medium, "wave");
}

// The warnings an object reports.
struct WarningCatcher
{
  std::string All;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    static_cast<WarningCatcher*>(clientData)->All += static_cast<const char*>(callData);
  }
};

// The medium's own-resolution grid in the reconstruction's output
// (partition 1), after a run with `limit` bytes for it; the warnings in
// `warnings`. The filters are gone when it returns.
vtkSmartPointer<vtkImageData> NativeImage(
  vtkImageData* field, vtkTypeInt64 limit, std::string& warnings, vtkTypeInt64 gpuLimit = 0)
{
  vtkSmartPointer<vtkPartitionedDataSetCollection> scene = Scene(field);
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(20000);
  tracer->SetSeed(3);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputDataObject(0, scene);
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(0, 0.4, 3);
  reconstruction->SetNativeMemoryLimit(limit);
  reconstruction->SetGPUMemoryLimit(gpuLimit);
  WarningCatcher catcher;
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback(WarningCatcher::Callback);
  command->SetClientData(&catcher);
  reconstruction->AddObserver(vtkCommand::WarningEvent, command);
  if (!reconstruction->GetExecutive()->Update())
  {
    return nullptr;
  }
  warnings = catcher.All;
  return vtkImageData::SafeDownCast(
    reconstruction->GetOutput()->GetPartitionedDataSet(1)->GetPartition(1));
}

// The cells of that grid.
std::array<int, 3> NativeCells(
  vtkImageData* field, vtkTypeInt64 limit, std::string& warnings, vtkTypeInt64 gpuLimit = 0)
{
  std::array<int, 3> cells{ 0, 0, 0 };
  vtkSmartPointer<vtkImageData> native = NativeImage(field, limit, warnings, gpuLimit);
  if (native)
  {
    int dims[3];
    native->GetDimensions(dims);
    cells = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
  }
  return cells;
}

// The output's extinction samples are the grid's own memory, not a copy:
// kept by the user after the filters, the scene and the field are gone,
// they are still there, whole.
void TestOutputOutlivesTheFilters()
{
  vtkSmartPointer<vtkImageData> native;
  std::vector<float> before;
  {
    vtkSmartPointer<vtkImageData> field = Field(24);
    std::string warnings;
    native = NativeImage(field, vtkTypeInt64(16) << 20, warnings);
    Check(native != nullptr, "the reconstruction runs");
    if (!native)
    {
      return;
    }
    // The classified field's scalars, read in place: the field's own
    // values (one per cell), lent, not copied.
    auto* samples = vtkFloatArray::SafeDownCast(
      native->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionCellValues));
    Check(samples && samples->GetNumberOfValues() == 24 * 24 * 24 &&
        !native->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionBrickSamples) &&
        samples->GetPointer(0) ==
          vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars())->GetPointer(0),
      "the grid's scalars are the field's values, in place");
    if (!samples)
    {
      return;
    }
    before.assign(samples->GetPointer(0), samples->GetPointer(0) + samples->GetNumberOfValues());
  }
  auto* samples = vtkFloatArray::SafeDownCast(
    native->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionCellValues));
  Check(samples && static_cast<std::size_t>(samples->GetNumberOfValues()) == before.size() &&
      std::equal(before.begin(), before.end(), samples->GetPointer(0)),
    "the output keeps its extinction samples after the filters are gone");
}

void TestOwnResolution()
{
  // 48^3 points: each grid (the extinction's and the scalars') stores
  // 7^3 bricks of 2 KB, about 0.7 MB.
  vtkSmartPointer<vtkImageData> field = Field(48);
  std::string warnings;
  const std::array<int, 3> own = NativeCells(field, vtkTypeInt64(16) << 20, warnings);
  Check(own == (std::array<int, 3>{ 48, 48, 48 }),
    "a 48^3 field under 16 MB is drawn at 48^3, not at " + std::to_string(own[0]));
  Check(warnings.find("coarsened") == std::string::npos, "no warning at its own resolution");
  // The default limit comes from the machine: a quarter of half its memory.
  vtkNew<vtkBrumeRadianceReconstruction> defaults;
  Check(defaults->GetNativeMemoryLimit() == 0 &&
      defaults->GetEffectiveNativeMemoryLimit() >= (vtkTypeInt64(64) << 20),
    "the default limit is the machine's, at least 64 MB");

  const std::array<int, 3> coarse = NativeCells(field, vtkTypeInt64(1) << 19, warnings);
  Check(coarse == (std::array<int, 3>{ 24, 24, 24 }),
    "under half a megabyte it is coarsened by 2, to 24^3, not " + std::to_string(coarse[0]));
  Check(warnings.find("Medium 'wave' is drawn at 24 x 24 x 24, its own 48 x 48 x 48 coarsened "
                      "by 2") != std::string::npos,
    "one warning says so, naming the medium: '" + warnings + "'");
}

// A GPU that has less free than the machine's limit (the render pass and
// brume's commands set it from GL_NVX_gpu_memory_info or GL_ATI_meminfo)
// bounds the automatic limit, and the warning names it; an explicit
// NativeMemoryLimit overrides it.
void TestGPUMemoryLimit()
{
  vtkNew<vtkBrumeRadianceReconstruction> r;
  const vtkTypeInt64 machine = r->GetEffectiveNativeMemoryLimit();
  r->SetGPUMemoryLimit(vtkTypeInt64(1) << 19);
  Check(r->GetEffectiveNativeMemoryLimit() == (vtkTypeInt64(1) << 19) &&
      r->IsNativeMemoryLimitedByGPU(),
    "a GPU with half a megabyte free bounds the automatic limit");
  r->SetGPUMemoryLimit(machine + 1);
  Check(r->GetEffectiveNativeMemoryLimit() == machine && !r->IsNativeMemoryLimitedByGPU(),
    "a GPU with more free than the machine's limit leaves it");
  r->SetGPUMemoryLimit(vtkTypeInt64(1) << 19);
  r->SetNativeMemoryLimit(vtkTypeInt64(16) << 20);
  Check(r->GetEffectiveNativeMemoryLimit() == (vtkTypeInt64(16) << 20) &&
      !r->IsNativeMemoryLimitedByGPU(),
    "an explicit NativeMemoryLimit overrides the GPU's");

  vtkSmartPointer<vtkImageData> field = Field(48);
  std::string warnings;
  const std::array<int, 3> coarse = NativeCells(field, 0, warnings, vtkTypeInt64(1) << 19);
  Check(coarse == (std::array<int, 3>{ 24, 24, 24 }),
    "under a GPU's half megabyte it is coarsened by 2, to 24^3, not " + std::to_string(coarse[0]));
  Check(warnings.find("coarsened by 2") != std::string::npos &&
      warnings.find("the GPU has free") != std::string::npos,
    "the warning names the GPU: '" + warnings + "'");
  const std::array<int, 3> own =
    NativeCells(field, vtkTypeInt64(16) << 20, warnings, vtkTypeInt64(1) << 19);
  Check(
    own == (std::array<int, 3>{ 48, 48, 48 }) && warnings.find("coarsened") == std::string::npos,
    "with 16 MB asked for, it keeps its own 48^3 whatever the GPU's limit, not " +
      std::to_string(own[0]));
}

// The density of the scene's one medium.
std::shared_ptr<const brume::DensityField> Density(vtkImageData* field)
{
  brume::Scene scene;
  const std::string error = vtkBrumeSceneConversion::ToScene(Scene(field), scene);
  Check(error.empty(), "the scene converts: " + error);
  return error.empty() ? scene.Media.at(0).Density : nullptr;
}

const brume::DensityField* ScalarsOf(const std::shared_ptr<const brume::DensityField>& density)
{
  const auto* classified = dynamic_cast<const brume::ClassifiedDensity*>(density.get());
  return classified ? &classified->GetScalars() : nullptr;
}

void TestConvertedOnce()
{
  vtkSmartPointer<vtkImageData> field = Field(20);
  const auto first = Density(field);
  const auto again = Density(field);
  Check(first && first == again, "the same arrays give the same converted density");

  // An edit of the opacity function classifies the same scalars again.
  vtkDataArray* opacity = field->GetFieldData()->GetArray(vtkBrumeNames::ScalarOpacity);
  opacity->SetComponent(1, 1, 0.3);
  opacity->Modified();
  const auto edited = Density(field);
  Check(edited && edited != first, "an edited function gives another density");
  Check(ScalarsOf(edited) && ScalarsOf(edited) == ScalarsOf(first),
    "... of the same converted scalars");
  Check(std::abs(edited->Evaluate(brume::Vec3(0.1f, 0.2f, -0.1f)) -
          static_cast<const brume::ClassifiedDensity&>(*edited).GetOpacity().Extinction(
            ScalarsOf(edited)->Evaluate(brume::Vec3(0.1f, 0.2f, -0.1f)))) < 1e-6f,
    "... classified by the new function");

  // New values in the array: converted again.
  vtkDataArray* wave = field->GetPointData()->GetArray("wave");
  wave->SetTuple1(0, 75.0);
  wave->Modified();
  const auto modified = Density(field);
  Check(
    modified && ScalarsOf(modified) != ScalarsOf(first), "modified scalars are converted again");

  // The array gone, a density still in use stays.
  const std::weak_ptr<const brume::DensityField> last = modified;
  field = nullptr;
  Check(!last.expired(), "a density in use stays while it is used");
}

void TestReleasedWithTheArray()
{
  // A float array is read in place: the medium holds the array, the cache
  // holds the converted field while the array lives, and nothing else.
  const std::size_t before = vtkBrumeSceneConversion::GetNumberOfCachedArrays();
  vtkWeakPointer<vtkDataArray> array;
  std::shared_ptr<const brume::DensityField> density;
  float expected = 0.f;
  const brume::Vec3 p(0.1f, 0.2f, -0.1f);
  {
    vtkSmartPointer<vtkImageData> field = Field(12);
    array = field->GetPointData()->GetArray("wave");
    density = Density(field);
    Check(density != nullptr, "the field converts");
    if (!density)
    {
      return;
    }
    expected = density->Evaluate(p);
    Check(vtkBrumeSceneConversion::GetNumberOfCachedArrays() == before + 1,
      "the cache keeps the converted field while its array lives");
  }
  Check(array != nullptr, "a density in use keeps the array whose memory it reads");
  Check(density->Evaluate(p) == expected, "... and reads the same values after the image is gone");
  density = nullptr;
  Check(array == nullptr, "the array goes with the last density made from it");
  Check(vtkBrumeSceneConversion::GetNumberOfCachedArrays() == before,
    "deleting the array lets its converted field go");
}

// A field whose array holds fewer values than its points (put together by
// hand) is refused with a message, not read past its end.
void TestMismatchedArray()
{
  vtkSmartPointer<vtkImageData> field = Field(8);
  field->GetPointData()->GetScalars()->SetNumberOfTuples(100);
  brume::Scene scene;
  const std::string error = vtkBrumeSceneConversion::ToScene(Scene(field), scene);
  Check(error.find("has 100 tuples in its density array 'wave', not the 512 of its 8 x 8 x 8 "
                   "points") != std::string::npos,
    "a short array is refused: '" + error + "'");
  // An inverted extent: dimensions below 1.
  field = Field(8);
  field->SetExtent(0, 7, 0, 7, 5, 0);
  const std::string inverted = vtkBrumeSceneConversion::ToScene(Scene(field), scene);
  Check(inverted.find("has an empty or inverted extent (8 x 8 x -4 points)") != std::string::npos,
    "an inverted extent is refused: '" + inverted + "'");
}

// 8- and 16-bit arrays are read in place, in their own type, and make the
// medium their values make as floats.
void TestTypedScalars()
{
  vtkNew<vtkFloatArray> rounded;
  vtkSmartPointer<vtkImageData> floats = Field(16, rounded);
  const auto expected = Density(floats);
  vtkNew<vtkUnsignedCharArray> bytes;
  vtkNew<vtkShortArray> shorts;
  for (vtkDataArray* array :
    { static_cast<vtkDataArray*>(bytes), static_cast<vtkDataArray*>(shorts) })
  {
    vtkSmartPointer<vtkImageData> field = Field(16, array);
    const auto density = Density(field);
    const auto* grid = dynamic_cast<const brume::GridDensity*>(ScalarsOf(density));
    Check(grid && grid->GetValues().Address() == array->GetVoidPointer(0) &&
        grid->GetValues().GetMemorySize() ==
          static_cast<std::size_t>(array->GetNumberOfValues() * array->GetDataTypeSize()),
      std::string("a ") + array->GetClassName() + " is read in place, in its own type");
    bool same = density && expected;
    for (int t = 0; same && t < 200; ++t)
    {
      const brume::Vec3 p(-0.45f + 0.0045f * t, 0.3f - 0.003f * t, 0.1f);
      same = density->Evaluate(p) == expected->Evaluate(p);
    }
    Check(same, std::string("... and its medium is the float array's: ") + array->GetClassName());
  }
}
}

int TestNativeResolution(int, char*[])
{
  TestOwnResolution();
  TestGPUMemoryLimit();
  TestConvertedOnce();
  TestReleasedWithTheArray();
  TestOutputOutlivesTheFilters();
  TestTypedScalars();
  TestMismatchedArray();
  if (failures)
  {
    std::cerr << failures << " check(s) failed\n";
    return 1;
  }
  return 0;
}
