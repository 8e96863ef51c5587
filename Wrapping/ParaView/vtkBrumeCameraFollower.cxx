// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeCameraFollower.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSessions.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyIterator.h"
#include "vtkSMProxyManager.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSmartPointer.h"

#include <cstring>

namespace
{
vtkSmartPointer<vtkCallbackCommand> ViewObserver;
vtkSmartPointer<vtkCallbackCommand> RegistrationObserver;

// Whether the reconstruction's textures are known not to depend on the
// viewpoint (its data information carries BrumeViewDependentObjects = 0):
// then moving its eye would only re-send the same textures.
bool ViewIndependent(vtkSMSourceProxy* source, unsigned int port)
{
  if (!source || port >= source->GetNumberOfOutputPorts())
  {
    return false;
  }
  vtkPVDataInformation* info = source->GetDataInformation(port);
  vtkPVArrayInformation* array = info
    ? info->GetArrayInformation(vtkBrumeNames::ViewDependentObjects, vtkDataObject::FIELD)
    : nullptr;
  if (!array || array->GetNumberOfComponents() != 1)
  {
    return false;
  }
  const double* range = array->GetComponentRange(0);
  return range[0] == 0.0 && range[1] == 0.0;
}

bool Same(const double a[3], const double b[3])
{
  for (int i = 0; i < 3; ++i)
  {
    if (static_cast<float>(a[i]) != static_cast<float>(b[i]))
    {
      return false;
    }
  }
  return true;
}

void BeforeRender(vtkObject* caller, unsigned long, void*, void*)
{
  vtkBrumeCameraFollower::Follow(vtkSMProxy::SafeDownCast(caller));
}

void Watch(vtkSMProxy* proxy)
{
  if (vtkSMRenderViewProxy::SafeDownCast(proxy) &&
    !proxy->HasObserver(vtkCommand::StartEvent, ViewObserver))
  {
    proxy->AddObserver(vtkCommand::StartEvent, ViewObserver);
  }
}

void Registered(vtkObject*, unsigned long, void*, void* data)
{
  const auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(data);
  if (info && info->Type == vtkSMProxyManager::RegisteredProxyInformation::PROXY)
  {
    Watch(info->Proxy);
  }
}

void WatchSession(vtkSMSession* session)
{
  vtkSMSessionProxyManager* manager = session ? session->GetSessionProxyManager() : nullptr;
  if (!manager || manager->HasObserver(vtkCommand::RegisterEvent, RegistrationObserver))
  {
    return;
  }
  manager->AddObserver(vtkCommand::RegisterEvent, RegistrationObserver);
  // The views that exist already (the GUI's first view, for one).
  vtkNew<vtkSMProxyIterator> views;
  views->SetSessionProxyManager(manager);
  views->SetModeToOneGroup();
  for (views->Begin("views"); !views->IsAtEnd(); views->Next())
  {
    Watch(views->GetProxy());
  }
}

}

void vtkBrumeCameraFollower::Install()
{
  if (ViewObserver || !vtkSMProxyManager::IsInitialized())
  {
    return;
  }
  ViewObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  ViewObserver->SetCallback(BeforeRender);
  RegistrationObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  RegistrationObserver->SetCallback(Registered);
  vtkBrumeWatchSessions(WatchSession);
}

int vtkBrumeCameraFollower::Follow(vtkSMProxy* proxy)
{
  auto* view = vtkSMRenderViewProxy::SafeDownCast(proxy);
  vtkCamera* camera = view ? view->GetActiveCamera() : nullptr;
  if (!camera || !view->GetProperty("Representations"))
  {
    return 0;
  }
  double position[3];
  camera->GetPosition(position);
  int moved = 0;
  vtkSMPropertyHelper representations(view, "Representations");
  for (unsigned int r = 0; r < representations.GetNumberOfElements(); ++r)
  {
    vtkSMProxy* representation = representations.GetAsProxy(r);
    if (!representation || !representation->GetProperty("FollowCamera") ||
      !representation->GetProperty("Input") || !representation->GetProperty("Visibility"))
    {
      continue;
    }
    if (representation->GetProperty("Representation"))
    {
      const char* type = vtkSMPropertyHelper(representation, "Representation").GetAsString();
      if (!type || std::strcmp(type, "Brume Radiance") != 0)
      {
        continue;
      }
    }
    if (vtkSMPropertyHelper(representation, "Visibility").GetAsInt() != 1 ||
      vtkSMPropertyHelper(representation, "FollowCamera").GetAsInt() != 1)
    {
      continue;
    }
    vtkSMPropertyHelper input(representation, "Input");
    vtkSMProxy* reconstruction = input.GetAsProxy();
    if (!reconstruction || !reconstruction->GetProperty("EyePosition") ||
      ViewIndependent(vtkSMSourceProxy::SafeDownCast(reconstruction), input.GetOutputPort()))
    {
      continue;
    }
    double eye[3];
    vtkSMPropertyHelper(reconstruction, "EyePosition").Get(eye, 3);
    if (Same(eye, position))
    {
      continue;
    }
    vtkSMPropertyHelper(reconstruction, "EyePosition").Set(position, 3);
    reconstruction->UpdateVTKObjects();
    ++moved;
  }
  return moved;
}
