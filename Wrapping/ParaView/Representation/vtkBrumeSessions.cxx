// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSessions.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkProcessModule.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSession.h"
#include "vtkSessionIterator.h"
#include "vtkSmartPointer.h"

namespace
{
void Connected(vtkObject*, unsigned long, void* clientData, void* callData)
{
  vtkProcessModule* module = vtkProcessModule::GetProcessModule();
  auto watch = reinterpret_cast<void (*)(vtkSMSession*)>(clientData);
  if (module && callData && watch)
  {
    watch(vtkSMSession::SafeDownCast(module->GetSession(*static_cast<vtkIdType*>(callData))));
  }
}
}

bool vtkBrumeWatchSessions(void (*watch)(vtkSMSession*))
{
  vtkProcessModule* module = vtkProcessModule::GetProcessModule();
  if (!module || !vtkSMProxyManager::IsInitialized() || !watch)
  {
    return false;
  }
  vtkNew<vtkCallbackCommand> connected;
  connected->SetCallback(Connected);
  connected->SetClientData(reinterpret_cast<void*>(watch));
  module->AddObserver(vtkCommand::ConnectionCreatedEvent, connected);
  vtkSmartPointer<vtkSessionIterator> sessions;
  sessions.TakeReference(module->NewSessionIterator());
  for (sessions->InitTraversal(); !sessions->IsDoneWithTraversal(); sessions->GoToNextItem())
  {
    watch(vtkSMSession::SafeDownCast(sessions->GetCurrentSession()));
  }
  return true;
}
