// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRenderViewInitializationHelper
 * @brief   a "Brume Render View" that replaces a view shows what it showed
 *
 * ParaView's "Convert To ..." (the view's title-bar menu) destroys the
 * view, then creates the new one empty: a user switching a render view to
 * Brume would have to show every source again and lose its colour maps.
 * When a Brume Render View is created right after a view was destroyed
 * (within Window seconds, with no proxy registered in between, in the same
 * session), this helper shows in it
 * what that view showed, each with its representation's settings (the
 * Volume representation, the array it was coloured by and its colour map
 * and opacity function), and takes its camera.
 *
 * It also makes a progressive view refine by itself in the GUI: after a
 * render that did not trace the whole budget, the view renders again once
 * the GUI's event loop is idle (a one-shot timer of its interactor), step
 * after step, the camera free to move meanwhile.
 *
 * Install() (at the plugin's load, on the client) watches the session
 * proxy managers for representations and views unregistered.
 *
 * Registered in the view's XML hints:
 * <InitializationHelper class="vtkBrumeRenderViewInitializationHelper"/>
 */
#ifndef vtkBrumeRenderViewInitializationHelper_h
#define vtkBrumeRenderViewInitializationHelper_h

#include "vtkBrumeParaViewRepresentationModule.h" // For export macro
#include "vtkSMProxyInitializationHelper.h"

class VTKBRUMEPARAVIEWREPRESENTATION_EXPORT vtkBrumeRenderViewInitializationHelper
  : public vtkSMProxyInitializationHelper
{
public:
  static vtkBrumeRenderViewInitializationHelper* New();
  vtkTypeMacro(vtkBrumeRenderViewInitializationHelper, vtkSMProxyInitializationHelper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void PostInitializeProxy(
    vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType initializationTimeStamp) override;

  /// Watches the processes' sessions for views destroyed (once per process).
  static void Install();

  /// How soon after a view is destroyed a new Brume Render View takes over.
  static constexpr double Window = 2.0;

protected:
  vtkBrumeRenderViewInitializationHelper() = default;
  ~vtkBrumeRenderViewInitializationHelper() override = default;

private:
  vtkBrumeRenderViewInitializationHelper(const vtkBrumeRenderViewInitializationHelper&) = delete;
  void operator=(const vtkBrumeRenderViewInitializationHelper&) = delete;
};

#endif
