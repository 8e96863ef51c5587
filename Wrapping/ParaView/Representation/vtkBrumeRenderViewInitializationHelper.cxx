// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRenderViewInitializationHelper.h"

#include "vtkBrumeSessions.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkProcessModule.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <chrono>
#include <cstring>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkBrumeRenderViewInitializationHelper);

namespace
{
using Clock = std::chrono::steady_clock;

// What the last destroyed view showed: its visible representations (kept
// alive until a new view copies them or they grow old) and its camera.
struct Destroyed
{
  Clock::time_point When;
  std::vector<vtkSmartPointer<vtkSMProxy>> Representations;
  vtkSmartPointer<vtkSMProxy> View;
};
Destroyed Last;
vtkSmartPointer<vtkCallbackCommand> UnregisterObserver;
vtkSmartPointer<vtkCallbackCommand> RegisterObserver;

double Age(Clock::time_point when)
{
  return std::chrono::duration<double>(Clock::now() - when).count();
}

void Unregistered(vtkObject*, unsigned long, void*, void* data)
{
  const auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(data);
  if (!info || info->Type != vtkSMProxyManager::RegisteredProxyInformation::PROXY || !info->Proxy ||
    !info->GroupName)
  {
    return;
  }
  if (Age(Last.When) > vtkBrumeRenderViewInitializationHelper::Window)
  {
    Last = Destroyed();
  }
  // A view's representations are unregistered before the view itself.
  if (std::strcmp(info->GroupName, "representations") == 0 &&
    info->Proxy->GetProperty("Visibility") && info->Proxy->GetProperty("Input") &&
    vtkSMPropertyHelper(info->Proxy, "Visibility").GetAsInt() != 0)
  {
    Last.Representations.emplace_back(info->Proxy);
    Last.When = Clock::now();
  }
  else if (std::strcmp(info->GroupName, "views") == 0)
  {
    Last.View = info->Proxy;
    Last.When = Clock::now();
  }
}

// Any proxy registered: what the destroyed view showed is let go (its
// representations were kept alive for the view that replaces it, which is
// initialized before it is registered).
void Registered(vtkObject*, unsigned long, void*, void*)
{
  Last = Destroyed();
}

void WatchSession(vtkSMSession* session)
{
  vtkSMSessionProxyManager* manager = session ? session->GetSessionProxyManager() : nullptr;
  if (manager && !manager->HasObserver(vtkCommand::UnRegisterEvent, UnregisterObserver))
  {
    manager->AddObserver(vtkCommand::UnRegisterEvent, UnregisterObserver);
    manager->AddObserver(vtkCommand::RegisterEvent, RegisterObserver);
  }
}

// Progressive views in the GUI: after a render that left particles to add
// (BrumeIsRefining), one more render once the interactor's
// event loop is idle, until it did. Keyed by view.
struct Refinement
{
  vtkWeakPointer<vtkSMViewProxy> View;
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
};
std::map<vtkSMProxy*, Refinement> Refining;
vtkSmartPointer<vtkCallbackCommand> RenderObserver;
vtkSmartPointer<vtkCallbackCommand> TimerObserver;

void Rendered(vtkObject* caller, unsigned long, void*, void*)
{
  auto* view = vtkSMViewProxy::SafeDownCast(caller);
  vtkRenderWindowInteractor* interactor = view ? view->GetInteractor() : nullptr;
  vtkSMProperty* refining = view ? view->GetProperty("BrumeIsRefining") : nullptr;
  if (!interactor || !refining || Refining.count(view))
  {
    return;
  }
  // Not "not converged": a view whose trace failed would render forever.
  view->UpdatePropertyInformation(refining);
  if (vtkSMPropertyHelper(refining).GetAsInt() == 0)
  {
    return;
  }
  Refining[view] = { view, interactor };
  if (!interactor->HasObserver(vtkCommand::TimerEvent, TimerObserver))
  {
    interactor->AddObserver(vtkCommand::TimerEvent, TimerObserver);
  }
  interactor->CreateOneShotTimer(1);
}

void TimerFired(vtkObject* caller, unsigned long, void*, void*)
{
  std::vector<vtkSMViewProxy*> due;
  for (auto it = Refining.begin(); it != Refining.end();)
  {
    if (it->second.Interactor == caller || !it->second.View || !it->second.Interactor)
    {
      if (it->second.View && it->second.Interactor)
      {
        due.push_back(it->second.View);
      }
      it = Refining.erase(it);
    }
    else
    {
      ++it;
    }
  }
  for (vtkSMViewProxy* view : due)
  {
    view->StillRender(); // the next step; Rendered() asks for another if needed
  }
}

// A session closed (the GUI disconnecting or quitting): nothing of it is
// kept, so that no proxy outlives its session in a static.
void SessionClosed(vtkObject*, unsigned long, void*, void*)
{
  Last = Destroyed();
  Refining.clear();
}

// The camera of the destroyed view, where the new one has the same
// properties.
void CopyCamera(vtkSMProxy* from, vtkSMProxy* to)
{
  for (const char* name : { "CameraPosition", "CameraFocalPoint", "CameraViewUp", "CameraViewAngle",
         "CameraParallelScale", "CameraParallelProjection", "CenterOfRotation", "RotationFactor" })
  {
    vtkSMProperty* source = from->GetProperty(name);
    vtkSMProperty* target = to->GetProperty(name);
    if (source && target)
    {
      target->Copy(source);
    }
  }
}
}

void vtkBrumeRenderViewInitializationHelper::Install()
{
  if (UnregisterObserver || !vtkSMProxyManager::IsInitialized())
  {
    return;
  }
  UnregisterObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  UnregisterObserver->SetCallback(Unregistered);
  RegisterObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  RegisterObserver->SetCallback(Registered);
  vtkNew<vtkCallbackCommand> closed;
  closed->SetCallback(SessionClosed);
  if (vtkProcessModule* module = vtkProcessModule::GetProcessModule())
  {
    module->AddObserver(vtkCommand::ConnectionClosedEvent, closed);
  }
  RenderObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  RenderObserver->SetCallback(Rendered);
  TimerObserver = vtkSmartPointer<vtkCallbackCommand>::New();
  TimerObserver->SetCallback(TimerFired);
  vtkBrumeWatchSessions(WatchSession);
}

void vtkBrumeRenderViewInitializationHelper::PostInitializeProxy(
  vtkSMProxy* proxy, vtkPVXMLElement*, vtkMTimeType)
{
  Destroyed last;
  std::swap(last, Last); // taken once, whatever happens
  auto* view = vtkSMViewProxy::SafeDownCast(proxy);
  if (view && RenderObserver && !view->HasObserver(vtkCommand::EndEvent, RenderObserver))
  {
    view->AddObserver(vtkCommand::EndEvent, RenderObserver);
  }
  if (!view || !last.View || Age(last.When) > Window)
  {
    return;
  }
  vtkSMSessionProxyManager* manager = proxy->GetSessionProxyManager();
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  for (const auto& old : last.Representations)
  {
    vtkSMPropertyHelper input(old, "Input");
    auto* source = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
    // Sources deleted since are not shown again.
    if (!source || old->GetSessionProxyManager() != manager ||
      !manager->GetProxyName("sources", source))
    {
      continue;
    }
    vtkSMProxy* shown = controller->Show(source, static_cast<int>(input.GetOutputPort()), view);
    if (shown && std::strcmp(shown->GetXMLName(), old->GetXMLName()) == 0)
    {
      // The representation's settings (its type, colouring, colour map
      // and opacity function), its input excepted.
      shown->Copy(old, "vtkSMInputProperty");
      shown->UpdateVTKObjects();
    }
  }
  CopyCamera(last.View, proxy);
  proxy->UpdateVTKObjects();
}

void vtkBrumeRenderViewInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
