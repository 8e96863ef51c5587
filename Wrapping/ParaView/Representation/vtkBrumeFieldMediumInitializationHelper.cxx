// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeFieldMediumInitializationHelper.h"

#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMTransferFunctionProxy.h"

#include <string>

vtkStandardNewMacro(vtkBrumeFieldMediumInitializationHelper);

namespace
{
// The input's array a display would colour by: the active point scalars,
// else the first one-component point array, else the same among cells.
vtkPVArrayInformation* DefaultScalars(vtkPVDataInformation* info, int& association)
{
  for (const int a :
    { vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataObject::FIELD_ASSOCIATION_CELLS })
  {
    vtkPVDataSetAttributesInformation* attributes = info->GetAttributeInformation(a);
    if (!attributes)
    {
      continue;
    }
    association = a;
    if (vtkPVArrayInformation* active =
          attributes->GetAttributeInformation(vtkDataSetAttributes::SCALARS))
    {
      return active;
    }
    for (int k = 0; k < attributes->GetNumberOfArrays(); ++k)
    {
      vtkPVArrayInformation* array = attributes->GetArrayInformation(k);
      if (array && array->GetNumberOfComponents() == 1)
      {
        return array;
      }
    }
  }
  return nullptr;
}

bool SetByUser(vtkSMProxy* proxy, const char* name, vtkMTimeType created)
{
  vtkSMProperty* property = proxy->GetProperty(name);
  return !property || property->GetMTime() > created;
}
}

void vtkBrumeFieldMediumInitializationHelper::PostInitializeProxy(
  vtkSMProxy* proxy, vtkPVXMLElement*, vtkMTimeType created)
{
  vtkSMSourceProxy* input =
    vtkSMSourceProxy::SafeDownCast(vtkSMPropertyHelper(proxy, "Input", true).GetAsProxy());
  if (!input || !proxy->GetProperty("SelectInputScalars"))
  {
    return;
  }
  const unsigned int port = vtkSMPropertyHelper(proxy, "Input").GetOutputPort();
  // The array and its range are what the input gives (as Apply would
  // update it).
  input->UpdatePipeline();
  vtkPVDataInformation* info = input->GetDataInformation(port);
  vtkSMPropertyHelper scalars(proxy, "SelectInputScalars");
  const char* chosen = scalars.GetInputArrayNameToProcess();
  std::string name = chosen ? chosen : "";
  int association = scalars.GetInputArrayAssociation();
  vtkPVArrayInformation* array =
    name.empty() ? nullptr : info->GetArrayInformation(name.c_str(), association);
  if (name.empty())
  {
    // No array chosen (the domain's default is empty while the input has
    // not run): the one a display would colour by.
    array = DefaultScalars(info, association);
    if (array && array->GetName())
    {
      name = array->GetName();
      scalars.SetInputArrayToProcess(association, name.c_str());
    }
  }
  if (name.empty())
  {
    return; // nothing to classify: the filter says so when it runs
  }
  vtkNew<vtkSMTransferFunctionManager> manager;
  vtkSMSessionProxyManager* pxm = proxy->GetSessionProxyManager();
  vtkSMProxy* colour = manager->GetColorTransferFunction(name.c_str(), pxm);
  vtkSMProxy* opacity = manager->GetOpacityTransferFunction(name.c_str(), pxm);
  // A function whose range was never set is fitted to the array's, as
  // colouring a display by the array does (unless its range is locked),
  // and marked set.
  const bool locked = colour &&
    vtkSMPropertyHelper(colour, "AutomaticRescaleRangeMode", true).GetAsInt() ==
      vtkSMTransferFunctionManager::NEVER;
  const bool initialized =
    colour && vtkSMPropertyHelper(colour, "ScalarRangeInitialized", true).GetAsInt() != 0;
  double range[2];
  if (colour && opacity && array && !locked && !initialized)
  {
    array->GetComponentRange(-1, range);
    if (range[0] <= range[1])
    {
      vtkSMTransferFunctionProxy::RescaleTransferFunction(colour, range);
      vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, range);
      for (vtkSMProxy* function : { colour, opacity })
      {
        if (function->GetProperty("ScalarRangeInitialized"))
        {
          vtkSMPropertyHelper(function, "ScalarRangeInitialized").Set(1);
          function->UpdateVTKObjects();
        }
      }
    }
  }
  if (colour && !SetByUser(proxy, "LookupTable", created))
  {
    vtkSMPropertyHelper(proxy, "LookupTable").Set(colour);
  }
  if (opacity && !SetByUser(proxy, "ScalarOpacityFunction", created))
  {
    vtkSMPropertyHelper(proxy, "ScalarOpacityFunction").Set(opacity);
  }
  proxy->UpdateVTKObjects();
}

void vtkBrumeFieldMediumInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
