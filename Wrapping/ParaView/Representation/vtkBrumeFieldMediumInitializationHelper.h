// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeFieldMediumInitializationHelper
 * @brief   "Brume Medium From Field" starts with the array's own transfer functions
 *
 * When the filter is created (from the menus or from Python), this helper
 * chooses the scalars the way ParaView's displays do (the input's active
 * point scalars, else its first one-component point array, else cell
 * array) and gives the filter that array's colour map and opacity
 * function: the ones the Color Map Editor edits and a Volume display of the
 * same array uses, so that one Apply makes a medium the user can edit
 * there. A function whose range was never set (ScalarRangeInitialized) is
 * first fitted to the array's range, as colouring a display by the array
 * does (unless its range is locked). Properties the user set while
 * creating the filter are left as they are.
 *
 * Registered in the filter's XML hints:
 * <InitializationHelper class="vtkBrumeFieldMediumInitializationHelper"/>
 */
#ifndef vtkBrumeFieldMediumInitializationHelper_h
#define vtkBrumeFieldMediumInitializationHelper_h

#include "vtkBrumeParaViewRepresentationModule.h" // For export macro
#include "vtkSMProxyInitializationHelper.h"

class VTKBRUMEPARAVIEWREPRESENTATION_EXPORT vtkBrumeFieldMediumInitializationHelper
  : public vtkSMProxyInitializationHelper
{
public:
  static vtkBrumeFieldMediumInitializationHelper* New();
  vtkTypeMacro(vtkBrumeFieldMediumInitializationHelper, vtkSMProxyInitializationHelper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void PostInitializeProxy(
    vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType initializationTimeStamp) override;

protected:
  vtkBrumeFieldMediumInitializationHelper() = default;
  ~vtkBrumeFieldMediumInitializationHelper() override = default;

private:
  vtkBrumeFieldMediumInitializationHelper(const vtkBrumeFieldMediumInitializationHelper&) = delete;
  void operator=(const vtkBrumeFieldMediumInitializationHelper&) = delete;
};

#endif
