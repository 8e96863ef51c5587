// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumePass: a VTK program's renderer lit by Brume with one added line.
// - A sphere, a ground and a Wavelet volume under a positional light,
//   through the pass, give the image of the explicit pipeline over the
//   same scene (vtkBrumeRendererScene + vtkBrumePipeline, tone-mapped as
//   brume render does), up to the display's 8-bit rounding.
// - A camera orbit traces nothing again and updates the view-dependent
//   textures; a colour edit traces once more.
// - Progressive frames: a sixteenth of the budget, then a quarter, then
//   all of it, each step's textures bitwise those of one run of its count.
// - Transfer-function edits keep what they did not change, and are
//   previewed (PreviewEdits) in one frame.
#include "VtkSceneTesting.h"
#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeOpenGLSliceVolumeMapper.h"
#include "vtkBrumePass.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeRendererScene.h"
#include "vtkBrumeSceneActors.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataObjectTree.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkWindowToImageFilter.h"

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 64;
constexpr vtkTypeInt64 Particles = 40000;

int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

// The textures of two reconstructions, bitwise: every array of every
// object.
bool SameTextures(vtkDataObject* a, vtkDataObject* b)
{
  auto* ca = vtkDataObjectTree::SafeDownCast(a);
  auto* cb = vtkDataObjectTree::SafeDownCast(b);
  if (!ca || !cb)
  {
    return false;
  }
  vtkSmartPointer<vtkDataObjectTreeIterator> ia;
  ia.TakeReference(ca->NewTreeIterator());
  vtkSmartPointer<vtkDataObjectTreeIterator> ib;
  ib.TakeReference(cb->NewTreeIterator());
  int compared = 0;
  for (ia->InitTraversal(), ib->InitTraversal(); !ia->IsDoneWithTraversal();
       ia->GoToNextItem(), ib->GoToNextItem())
  {
    auto* da = vtkDataSet::SafeDownCast(ia->GetCurrentDataObject());
    auto* db =
      ib->IsDoneWithTraversal() ? nullptr : vtkDataSet::SafeDownCast(ib->GetCurrentDataObject());
    if (!da || !db)
    {
      return false;
    }
    for (vtkFieldData* fa : { static_cast<vtkFieldData*>(da->GetPointData()),
           static_cast<vtkFieldData*>(da->GetCellData()), da->GetFieldData() })
    {
      vtkFieldData* fb = fa == da->GetPointData() ? static_cast<vtkFieldData*>(db->GetPointData())
        : fa == da->GetCellData()                 ? static_cast<vtkFieldData*>(db->GetCellData())
                                                  : db->GetFieldData();
      for (int i = 0; i < fa->GetNumberOfArrays(); ++i)
      {
        vtkDataArray* x = fa->GetArray(i);
        vtkDataArray* y = x && x->GetName() ? fb->GetArray(x->GetName()) : nullptr;
        if (!x)
        {
          continue;
        }
        if (!y || x->GetDataType() != y->GetDataType() ||
          x->GetNumberOfValues() != y->GetNumberOfValues() ||
          std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0),
            static_cast<std::size_t>(x->GetNumberOfValues()) * x->GetDataTypeSize()) != 0)
        {
          return false;
        }
        ++compared;
      }
    }
  }
  return ib->IsDoneWithTraversal() && compared > 0;
}

// Progressive frames: a first step, then steps growing the count fourfold to the
// budget, each step's textures bitwise those of one run of its count (at
// the same resolutions); a ProgressEvent after each.
void TestProgressive(vtkRenderer* renderer, vtkRenderWindow* window, vtkBrumePass* pass)
{
  auto resolutions = [](vtkBrumePipeline* p)
  {
    p->GetReconstruction()->SetSurfaceResolution(24);
    p->GetReconstruction()->SetMediumResolution(10);
  };
  resolutions(pass->GetPipeline());
  pass->ProgressiveOn();
  pass->SetFirstStepParticles(Particles / 16);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&progress);
  observer->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData)
    { static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData)); });
  pass->AddObserver(vtkCommand::ProgressEvent, observer);
  const int traces = pass->GetNumberOfTraces();
  vtkNew<vtkBrumeRendererScene> scene;
  scene->SetRenderer(renderer);
  bool same = true;
  int frames = 0;
  bool refining = true; // while steps remain
  bool quick = true;    // slab sampling off exactly while steps remain
  for (; frames < 10 && (frames == 0 || !pass->IsConverged()); ++frames)
  {
    window->Render();
    refining = refining && (pass->IsRefining() == !pass->IsConverged());
    // Frames the next steps replace are quick draws: one sample a slab.
    quick = quick && (pass->GetPipeline()->GetActors()->GetSlabSampling() == pass->IsConverged());
    const vtkTypeInt64 count = pass->GetPipeline()->GetTracer()->GetNumberOfParticles();
    vtkNew<vtkBrumePipeline> once;
    once->SetInputConnection(scene->GetOutputPort());
    once->SetCamera(renderer->GetActiveCamera());
    once->GetTracer()->SetNumberOfParticles(count);
    resolutions(once);
    same = same && once->Update() &&
      SameTextures(pass->GetPipeline()->GetReconstruction()->GetOutputDataObject(0),
        once->GetReconstruction()->GetOutputDataObject(0));
    std::cout << "progressive frame " << frames << ": " << count << " particles\n";
  }
  Check(frames == 3 && pass->IsConverged() && pass->GetNumberOfTraces() == traces + 1 &&
      pass->GetNumberOfSteps() == 2,
    "a change, then two steps: the budget's sixteenth, quarter and whole in three frames");
  Check(same, "each step's textures are bitwise those of one run of its count");
  Check(refining && !pass->IsRefining(), "IsRefining() while steps remain, not once converged");
  Check(quick && pass->GetPipeline()->GetActors()->GetSlabSampling(),
    "the media drawn with one sample a slab while steps remain, with the full count once "
    "converged");
  Check(progress.size() == 3 && progress[0] == 0.0625 && progress[1] == 0.25 && progress[2] == 1.0,
    "a ProgressEvent after each step, with the fraction traced");
  const int steps = pass->GetNumberOfSteps();
  window->Render();
  Check(pass->GetNumberOfSteps() == steps && pass->GetNumberOfTraces() == traces + 1,
    "once converged, a frame traces nothing");
}

// Edits of a volume's transfer functions: the reconstruction takes from the
// textures it replaces the bricks of extinction an opacity edit left as
// they were (all of them after a colour edit), and its textures are
// bitwise those of a fresh pipeline over the edited scene.
// An off-screen window of Size^2 pixels showing `renderer`.
void OffScreen(vtkRenderWindow* window, vtkRenderer* renderer)
{
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(Size, Size);
  window->AddRenderer(renderer);
}

// The scene of the edit tests: a ground, a 49^3 Wavelet (7^3 bricks, the
// outer ones below 200 and the centre above) classified after trilinear
// interpolation (bricks of nearest values are sampled again at every edit
// of the opacity), a point light, and the camera; the Wavelet's volume.
vtkVolume* AddEditScene(vtkRenderer* renderer)
{
  AddGround(renderer, 0.7, 0.7, 0.7);
  const double where[3] = { 0, 0, 0 };
  vtkVolume* volume = AddWavelet(renderer, 24, 90, 280, 0.6, 0.03, where);
  volume->GetProperty()->SetInterpolationTypeToLinear();
  const double lightPosition[3] = { 1, 4, 3 };
  AddPointLight(renderer, lightPosition, 30);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 1, 4);
  camera->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  return volume;
}

void TestTransferFunctionEdits()
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  OffScreen(window, renderer);
  vtkVolume* volume = AddEditScene(renderer);
  vtkPiecewiseFunction* opacity = volume->GetProperty()->GetScalarOpacity();
  opacity->AddPoint(150, 0.02);
  opacity->AddPoint(200, 0.1);
  vtkColorTransferFunction* colour = volume->GetProperty()->GetRGBTransferFunction();
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkBrumePass> pass;
  pass->SetNumberOfParticles(Particles);
  pass->ProgressiveOff();
  renderer->SetPass(pass);
  vtkBrumeRadianceReconstruction* reconstruction = pass->GetPipeline()->GetReconstruction();
  vtkNew<vtkBrumeRendererScene> scene;
  scene->SetRenderer(renderer);
  auto asFresh = [&]()
  {
    vtkNew<vtkBrumePipeline> once;
    once->SetInputConnection(scene->GetOutputPort());
    once->SetCamera(camera);
    once->GetTracer()->SetNumberOfParticles(Particles);
    return once->Update() &&
      SameTextures(
        reconstruction->GetOutputDataObject(0), once->GetReconstruction()->GetOutputDataObject(0));
  };
  auto mediumMapper = [&]()
  {
    vtkBrumeOpenGLSliceVolumeMapper* found = nullptr;
    vtkPropCollection* props = pass->GetPipeline()->GetActors()->GetProps();
    props->InitTraversal();
    for (vtkProp* prop = props->GetNextProp(); prop; prop = props->GetNextProp())
    {
      if (auto* medium = vtkVolume::SafeDownCast(prop))
      {
        found = vtkBrumeOpenGLSliceVolumeMapper::SafeDownCast(medium->GetMapper());
      }
    }
    return found;
  };
  window->Render();
  vtkBrumeOpenGLSliceVolumeMapper* firstMapper = mediumMapper();
  const vtkIdType all = reconstruction->GetNumberOfNativeBricksSampled();
  Check(all > 0 && reconstruction->GetNumberOfNativeBricksReused() == 0,
    "the first trace samples every brick");

  // The opacity above 200 only.
  opacity->AddPoint(280, 0.9);
  window->Render();
  const vtkIdType sampled = reconstruction->GetNumberOfNativeBricksSampled() - all;
  const vtkIdType reused = reconstruction->GetNumberOfNativeBricksReused();
  std::cout << "an opacity edit above 200: " << sampled << " of " << all
            << " bricks sampled again, " << reused << " kept\n";
  Check(pass->GetNumberOfTraces() == 2 && sampled > 0 && reused > 0 && sampled + reused == all,
    "an opacity edit samples again only the bricks whose scalars it changed");
  Check(reconstruction->GetNumberOfDirectLightsKept() == 0,
    "an opacity edit casts the shadow rays again");
  Check(asFresh(), "after the opacity edit, the textures of a fresh pipeline");

  // The colour only: every brick kept.
  colour->AddRGBPoint(200, 1.0, 0.2, 0.1);
  window->Render();
  Check(pass->GetNumberOfTraces() == 3 &&
      reconstruction->GetNumberOfNativeBricksSampled() == all + sampled &&
      reconstruction->GetNumberOfNativeBricksReused() == reused + all,
    "a colour edit keeps every brick");
  // The ground and the medium: their shadow rays are those cast before.
  Check(reconstruction->GetNumberOfDirectLightsKept() == 2,
    "a colour edit keeps the direct light's shadow rays (kept " +
      std::to_string(reconstruction->GetNumberOfDirectLightsKept()) + ")");
  Check(asFresh(), "after the colour edit, the textures of a fresh pipeline");

  // Neither edit changed where the function is 0, so the scalars' bricks
  // were kept too: the pass kept its props (the same objects), and the
  // slice mapper did not send its atlas again; a mapper that sends
  // everything anew draws the same frame.
  vtkBrumeOpenGLSliceVolumeMapper* mapper = mediumMapper();
  Check(mapper && mapper == firstMapper, "the pass keeps the medium's mapper over the edits");
  Check(mapper && mapper->GetNumberOfExtinctionAtlasUploads() == 1,
    "the atlas of scalars sent once over three traces (sent " +
      std::to_string(mapper ? mapper->GetNumberOfExtinctionAtlasUploads() : -1) + ")");
  auto frame = [&]()
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    vtkNew<vtkUnsignedCharArray> pixels;
    pixels->DeepCopy(grab->GetOutput()->GetPointData()->GetScalars());
    return vtkSmartPointer<vtkUnsignedCharArray>(pixels);
  };
  auto kept = frame();
  vtkIdType lit = 0;
  for (vtkIdType v = 0; v < kept->GetNumberOfValues(); ++v)
  {
    lit += kept->GetValue(v) > 0 ? 1 : 0;
  }
  Check(lit > kept->GetNumberOfValues() / 4, "the edited scene is drawn");
  if (mapper)
  {
    mapper->ReleaseGraphicsResources(window);
    window->Render();
    auto sent = frame();
    Check(mapper->GetNumberOfExtinctionAtlasUploads() == 2 &&
        kept->GetNumberOfValues() == sent->GetNumberOfValues() &&
        std::memcmp(kept->GetVoidPointer(0), sent->GetVoidPointer(0),
          static_cast<std::size_t>(kept->GetNumberOfValues())) == 0,
      "the frame drawn from the kept atlas is the frame of an atlas sent anew");
    // The 16-bit tolerance through the pass's props: 0 sends the float
    // Wavelet's atlas again as floats at the next frame, nothing traced.
    const int bytes = mapper->GetExtinctionAtlasTexelBytes();
    const vtkIdType traces = pass->GetNumberOfTraces();
    pass->GetPipeline()->GetActors()->SetExtinctionDepthTolerance(0.0);
    window->Render();
    std::cout << "the atlas at the default tolerance: " << bytes
              << " bytes a texel; at 0: " << mapper->GetExtinctionAtlasTexelBytes() << " ("
              << mapper->GetNumberOfExtinctionAtlasUploads() << " uploads)\n";
    Check(bytes == 2 && mapper->GetExtinctionDepthTolerance() == 0.0 &&
        mapper->GetExtinctionAtlasTexelBytes() == 4 &&
        mapper->GetNumberOfExtinctionAtlasUploads() == 3 && pass->GetNumberOfTraces() == traces,
      "a tolerance of 0 on the pass's props sends the atlas again as floats");
  }
}

}

// The pixels of the window's last frame (not rendered again).
vtkSmartPointer<vtkUnsignedCharArray> Frame(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ShouldRerenderOff();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
  pixels->DeepCopy(grab->GetOutput()->GetPointData()->GetScalars());
  return pixels;
}

bool SameBytes(vtkDataArray* a, vtkDataArray* b)
{
  return a && b && a->GetDataType() == b->GetDataType() &&
    a->GetNumberOfValues() == b->GetNumberOfValues() &&
    std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
      static_cast<std::size_t>(a->GetNumberOfValues()) * a->GetDataTypeSize()) == 0;
}

// PreviewEdits: the first frame after an edit of a volume's transfer
// functions draws the last light under the new functions, with the table
// the trace then gives (bitwise), and traces nothing; the next frame
// traces, and the converged frames are those of a pass without previews
// (bitwise). An edit undone before its trace shows the last frame again;
// an edit that gives extinction where the old function left bricks out,
// and an edit of a light, are traced at once.
void TestPreviewEdits()
{
  auto run = [](bool preview)
  {
    std::vector<vtkSmartPointer<vtkUnsignedCharArray>> converged;
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    OffScreen(window, renderer);
    vtkVolume* volume = AddEditScene(renderer);
    vtkPiecewiseFunction* opacity = volume->GetProperty()->GetScalarOpacity();
    opacity->AddPoint(170, 0.0); // nothing below 170: the outer bricks left out
    vtkColorTransferFunction* colour = volume->GetProperty()->GetRGBTransferFunction();
    auto* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
    vtkNew<vtkBrumePass> pass;
    pass->SetNumberOfParticles(Particles);
    pass->SetFirstStepParticles(Particles / 16);
    pass->SetPreviewEdits(preview);
    renderer->SetPass(pass);
    auto converge = [&]()
    {
      for (int frames = 0; frames < 20 && !(frames > 0 && pass->IsConverged()); ++frames)
      {
        window->Render();
      }
      converged.push_back(Frame(window));
    };
    auto mapper = [&]() { return pass->GetPipeline()->GetActors()->GetMediumMapper(1); };
    auto table = [&]()
    {
      vtkImageData* extinction = mapper() ? mapper()->GetExtinctionData() : nullptr;
      vtkNew<vtkFloatArray> copy;
      if (vtkDataArray* t = extinction
          ? extinction->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionTransferFunction)
          : nullptr)
      {
        copy->DeepCopy(t);
      }
      return vtkSmartPointer<vtkFloatArray>(copy);
    };
    converge();
    Check(pass->GetNumberOfPreviews() == 0, "the first frame is traced, not previewed");
    if (preview)
    {
      // An edit undone before its trace: the traced textures shown again.
      auto before = Frame(window);
      const int traces = pass->GetNumberOfTraces();
      opacity->AddPoint(210, 0.6);
      window->Render();
      Check(!SameBytes(before, Frame(window)), "the preview of an edit to undo differs");
      opacity->RemovePoint(210);
      window->Render();
      Check(pass->GetNumberOfPreviews() == 1 && pass->GetNumberOfTraces() == traces &&
          pass->IsConverged() && SameBytes(before, Frame(window)),
        "an edit undone after its preview traces nothing and shows the last frame again");
    }
    const int base = pass->GetNumberOfPreviews();
    // The edits that only a table changes: the opacity above 200, then a colour.
    for (int edit = 0; edit < 2; ++edit)
    {
      auto before = Frame(window);
      if (edit == 0)
      {
        opacity->AddPoint(240, 0.5);
      }
      else
      {
        colour->AddRGBPoint(200, 1.0, 0.2, 0.1);
      }
      if (!preview)
      {
        converge();
        continue;
      }
      const int traces = pass->GetNumberOfTraces();
      auto oldTable = table();
      const int slices = mapper() ? mapper()->GetLastNumberOfSlices() : 0;
      window->Render();
      Check(pass->GetNumberOfPreviews() == base + edit + 1 && pass->GetNumberOfTraces() == traces &&
          !pass->IsConverged() && pass->IsRefining(),
        "edit " + std::to_string(edit) + " is previewed, nothing traced");
      auto previewTable = table();
      vtkBrumeSceneActors* actors = pass->GetPipeline()->GetActors();
      Check(actors->GetLastImageSampleDistance() == pass->GetPreviewImageSampleDistance(),
        "the preview's media drawn at the preview's image sample distance");
      // Half the slices, give or take one: their count is the depth over the spacing, rounded up.
      const int previewSlices = mapper() ? mapper()->GetLastNumberOfSlices() : 0;
      Check(slices > 4 && std::abs(2 * previewSlices - slices) <= 2,
        "the preview's slices twice as far apart: " + std::to_string(previewSlices) + " of " +
          std::to_string(slices));
      Check(!SameBytes(before, Frame(window)), "the preview draws the edited functions");
      Check(edit == 1 || !SameBytes(oldTable, previewTable), "the preview's table is new");
      window->Render();
      Check(pass->GetNumberOfTraces() == traces + 1 && actors->GetLastImageSampleDistance() == 1.0,
        "the frame after a preview traces, its media at the window's resolution");
      Check(actors->GetSliceSpacingScale() == 1.0 && mapper() &&
          mapper()->GetLastNumberOfSlices() == slices,
        "and at the actors' own slice spacing");
      Check(SameBytes(previewTable, table()), "the preview's table is the trace's");
      converge();
    }
    // Left-out bricks given an extinction: traced at once.
    vtkImageData* extinction = mapper() ? mapper()->GetExtinctionData() : nullptr;
    vtkDataArray* slots = extinction
      ? extinction->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionBrickSlots)
      : nullptr;
    bool leftOut = false;
    for (vtkIdType b = 0; slots && b < slots->GetNumberOfTuples(); ++b)
    {
      leftOut = leftOut || slots->GetTuple1(b) < 0;
    }
    Check(leftOut, "the function leaves bricks out");
    opacity->AddPoint(120, 0.3);
    int traces = pass->GetNumberOfTraces();
    window->Render();
    Check(pass->GetNumberOfPreviews() == base + (preview ? 2 : 0) &&
        pass->GetNumberOfTraces() == traces + 1,
      "an edit that gives extinction to bricks left out is traced at once");
    converge();
    light->SetIntensity(20);
    traces = pass->GetNumberOfTraces();
    window->Render();
    Check(pass->GetNumberOfPreviews() == base + (preview ? 2 : 0) &&
        pass->GetNumberOfTraces() == traces + 1,
      "a light's edit is traced at once");
    converge();
    return converged;
  };
  const auto with = run(true);
  const auto without = run(false);
  Check(with.size() == without.size(), "as many converged frames with previews as without");
  for (std::size_t i = 0; i < std::min(with.size(), without.size()); ++i)
  {
    Check(SameBytes(with[i], without[i]),
      "converged frame " + std::to_string(i) + " with previews is the frame without");
  }
}

int TestBrumePass(int, char*[])
{
  // The VTK program.
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  OffScreen(window, renderer);
  auto ground = AddPassScene(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();

  // The added line (and the budget, at once).
  vtkNew<vtkBrumePass> pass;
  pass->SetNumberOfParticles(Particles);
  pass->ProgressiveOff();
  renderer->SetPass(pass);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto* shown = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  Check(pass->GetNumberOfTraces() == 1, "the first frame traces once");

  // The explicit pipeline over the same scene.
  vtkNew<vtkBrumeRendererScene> scene;
  scene->SetRenderer(renderer);
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(scene->GetOutputPort());
  pipeline->SetCamera(camera);
  pipeline->SetSize(Size, Size);
  pipeline->GetTracer()->SetNumberOfParticles(Particles);
  Check(pipeline->Update(), "the explicit pipeline updates");
  vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();
  vtkSmartPointer<vtkImageData> expected = image ? pipeline->ToneMap(image) : nullptr;
  auto* reference =
    expected ? vtkUnsignedCharArray::SafeDownCast(expected->GetPointData()->GetScalars()) : nullptr;
  int largest = 256;
  vtkIdType off = 0, lit = 0;
  if (shown && reference && shown->GetNumberOfTuples() == reference->GetNumberOfTuples())
  {
    largest = 0;
    for (vtkIdType i = 0; i < reference->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        const int d = std::abs(static_cast<int>(shown->GetComponent(i, c)) -
          static_cast<int>(reference->GetComponent(i, c)));
        largest = std::max(largest, d);
        off += d > 1 ? 1 : 0;
        lit += reference->GetComponent(i, c) > 0 ? 1 : 0;
      }
    }
  }
  if (const char* dump = std::getenv("BRUME_TEST_DUMP"))
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName((std::string(dump) + "-pass.png").c_str());
    writer->SetInputData(grab->GetOutput());
    writer->Write();
    writer->SetFileName((std::string(dump) + "-pipeline.png").c_str());
    writer->SetInputData(expected);
    writer->Write();
  }
  std::cout << "pass against the explicit pipeline: largest difference " << largest << " of 255, "
            << off << " values off by more than 1, " << lit << " lit values\n";
  Check(largest <= 1 && lit > Size * Size, "the pass shows the explicit pipeline's image");

  // A camera orbit: no new trace, view-dependent updates (the glossy ball).
  vtkBrumeRadianceReconstruction* reconstruction = pass->GetPipeline()->GetReconstruction();
  const vtkIdType updates = reconstruction->GetNumberOfViewUpdates();

  for (int k = 0; k < 36; ++k)
  {
    camera->Azimuth(10);
    window->Render();
  }
  std::cout << "traces " << pass->GetNumberOfTraces() << ", view updates "
            << pass->GetNumberOfViewUpdates() << " after the orbit\n";
  Check(pass->GetNumberOfTraces() == 1 && pass->GetNumberOfViewUpdates() == 36 &&
      pass->GetNumberOfReconstructions() == 1,
    "a camera orbit of 36 frames: no new trace, 36 view updates");
  Check(reconstruction->GetNumberOfViewUpdates() >= updates + 36,
    "each new view updates the view-dependent textures");
  ground->GetProperty()->SetColor(0.3, 0.6, 0.9);
  window->Render();
  window->Render();
  Check(pass->GetNumberOfTraces() == 2 && pass->GetNumberOfViewUpdates() == 36,
    "a colour edit traces once more (and is no view update)");

  TestProgressive(renderer, window, pass);
  TestTransferFunctionEdits();
  TestPreviewEdits();

  // A scene that cannot be traced (a rotated volume is refused): not
  // converged, and nothing to refine either, so that a program rendering
  // while IsRefining() (the ParaView GUI) stops.
  vtkVolumeCollection* volumes = renderer->GetVolumes();
  volumes->InitTraversal();
  vtkVolume* volume = volumes->GetNextVolume();
  Check(volume != nullptr, "the scene has a volume");
  if (volume)
  {
    volume->RotateY(30);
    std::cerr << "(errors expected below)\n";
    window->Render();
    Check(!pass->IsConverged() && !pass->IsRefining(),
      "a failed trace is neither converged nor refining (converged " +
        std::to_string(pass->IsConverged()) + ", refining " + std::to_string(pass->IsRefining()) +
        ")");
  }
  if (Failures == 0)
  {
    std::cout << "vtkBrumePass: the explicit pipeline's image, traces only on edits: ok\n";
  }
  return Failures == 0 ? 0 : 1;
}
