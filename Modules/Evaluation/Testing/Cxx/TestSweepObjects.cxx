// SPDX-License-Identifier: BSD-3-Clause
// Which medium and which surface vtkBrumeStabilitySweep edits, on small
// scenes: the first medium, the most visible non-emissive surface, the
// names asked for, and clear errors for names the scene does not have.
#include "EvaluationTestScenes.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeStabilitySweep.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkPartitionedDataSet.h"
#include "vtkStringArray.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
int Failures = 0;

void ExpectName(const char* chosen, const char* expected, const char* what)
{
  const bool ok = expected ? chosen && std::string(chosen) == expected : chosen == nullptr;
  if (!ok)
  {
    std::cerr << "FAILED: " << what << ": '" << (chosen ? chosen : "(error)") << "' instead of '"
              << (expected ? expected : "(error)") << "'\n";
    ++Failures;
  }
}

// In collection order: an emitter filling the view behind everything, a
// medium, a large surface, another medium, a small surface.
vtkSmartPointer<vtkPartitionedDataSetCollection> Wall()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double g0[3] = { -5, -5, -3 }, g1[3] = { 5, -5, -3 }, g2[3] = { 5, 5, -3 },
               g3[3] = { -5, 5, -3 };
  AddQuad(scene, "glow", g0, g1, g2, g3, 1.0);
  const double h0[3] = { -1, -1, -1 }, h1[3] = { 1, 1, -0.5 };
  AddMedium(scene, "haze", h0, h1);
  const double p0[3] = { -0.8, -0.8, 0 }, p1[3] = { 0.8, -0.8, 0 }, p2[3] = { 0.8, 0.8, 0 },
               p3[3] = { -0.8, 0.8, 0 };
  AddQuad(scene, "poster", p0, p1, p2, p3);
  const double q0[3] = { 0.2, 0.2, 1 }, q1[3] = { 0.4, 0.4, 1.2 };
  AddMedium(scene, "puff", q0, q1);
  const double t0[3] = { 0.9, -0.2, 0.5 }, t1[3] = { 1.2, -0.2, 0.5 }, t2[3] = { 1.2, 0.2, 0.5 },
               t3[3] = { 0.9, 0.2, 0.5 };
  AddQuad(scene, "tile", t0, t1, t2, t3);
  return scene;
}
}

int TestSweepObjects(int, char*[])
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&errors);
  count->SetCallback([](vtkObject*, unsigned long, void* n, void*) { ++*static_cast<int*>(n); });
  vtkNew<vtkBrumeStabilitySweep> sweep;
  sweep->AddObserver(vtkCommand::ErrorEvent, count);
  sweep->SetSize(32, 32);

  const auto wall = Wall();
  ExpectName(sweep->ChooseMedium(wall), "haze", "the first medium");
  ExpectName(sweep->ChooseSurface(wall), "poster", "the most visible non-emissive surface");
  sweep->SetMediumName("puff");
  sweep->SetSurfaceName("tile");
  ExpectName(sweep->ChooseMedium(wall), "puff", "the medium asked for");
  ExpectName(sweep->ChooseSurface(wall), "tile", "the surface asked for");
  sweep->SetMediumName("poster");
  sweep->SetSurfaceName("haze");
  ExpectName(sweep->ChooseMedium(wall), nullptr, "a surface is not a medium");
  ExpectName(sweep->ChooseSurface(wall), nullptr, "a medium is not a surface");
  sweep->SetMediumName("fog");
  sweep->SetSurfaceName("floor");
  ExpectName(sweep->ChooseMedium(wall), nullptr, "no medium of that name");
  ExpectName(sweep->ChooseSurface(wall), nullptr, "no surface of that name");
  if (errors != 4)
  {
    std::cerr << "FAILED: " << errors << " errors reported instead of 4\n";
    ++Failures;
  }
  sweep->SetMediumName(nullptr);
  sweep->SetSurfaceName(nullptr);

  // Without media, and without a non-emissive surface: nothing to edit.
  const auto gallery = Gallery(false);
  ExpectName(sweep->ChooseMedium(gallery), "", "a scene without media");
  auto glowOnly = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double g0[3] = { -1, -1, 0 }, g1[3] = { 1, -1, 0 }, g2[3] = { 1, 1, 0 },
               g3[3] = { -1, 1, 0 };
  AddQuad(glowOnly, "glow", g0, g1, g2, g3, 1.0);
  const double lower[3] = { -0.5, -0.5, 0.5 }, upper[3] = { 0.5, 0.5, 1.5 };
  AddMedium(glowOnly, "cloud", lower, upper);
  ExpectName(sweep->ChooseSurface(glowOnly), "", "a scene whose only surface emits");
  ExpectName(sweep->ChooseMedium(glowOnly), "cloud", "its medium");

  // The built-in scene: its fog, and its back wall (the largest in view),
  // which is why `brume chart --sweep` names the floor for it.
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  ExpectName(sweep->ChooseMedium(source->GetOutput()), "fog", "the default scene's medium");
  ExpectName(sweep->ChooseSurface(source->GetOutput()), "back", "the default scene's surface");

  // A medium read from an OpenVDB file takes its box and density from the
  // file, not from its image: the cases that reshape its grid (sheets, the
  // medium grown through a surface) are not run; asked for alone, they
  // are no case of the sweep. (The file is never opened: the names are
  // given, and the cases are chosen before anything is rendered.)
  auto vdb = Wall();
  vtkNew<vtkStringArray> file;
  file->SetName(vtkBrumeNames::VDBFile);
  file->InsertNextValue("haze.vdb");
  vdb->GetPartitionedDataSet(1)->GetPartition(0)->GetFieldData()->AddArray(file);
  sweep->SetInputData(vdb);
  sweep->SetMediumName("haze");
  sweep->SetSurfaceName("poster");
  std::string said;
  vtkNew<vtkCallbackCommand> keep;
  keep->SetClientData(&said);
  keep->SetCallback([](vtkObject*, unsigned long, void* text, void* message)
    { *static_cast<std::string*>(text) = static_cast<const char*>(message); });
  sweep->AddObserver(vtkCommand::ErrorEvent, keep);
  for (const char* reshaping : { "sheet voxels", "surface in medium" })
  {
    said.clear();
    sweep->SetParameter(reshaping);
    if (sweep->GetExecutive()->Update() != 0 ||
      said.find("No case of the sweep varies") == std::string::npos)
    {
      std::cerr << "FAILED: '" << reshaping << "' ran on a medium read from an OpenVDB file\n";
      ++Failures;
    }
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
