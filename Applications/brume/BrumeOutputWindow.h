// SPDX-License-Identifier: BSD-3-Clause
// What `brume` prints of VTK's messages: each error or warning as one
// line, "brume: MESSAGE" (without VTK's file, line, class and address), and
// nothing of the pipeline's own report that an algorithm failed (the
// vtkInformation dump that follows every failed request), which a user
// reads as a crash. BRUME_VTK_MESSAGES=1 keeps VTK's own output.
#ifndef BrumeOutputWindow_h
#define BrumeOutputWindow_h

#include "vtkOutputWindow.h"

#include <string> // For Message

class BrumeOutputWindow : public vtkOutputWindow
{
public:
  static BrumeOutputWindow* New();
  vtkTypeMacro(BrumeOutputWindow, vtkOutputWindow);

  /// Makes it VTK's output window, unless BRUME_VTK_MESSAGES is set.
  static void Install();

  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;

  /// The message of VTK's formatted text ("ERROR: In FILE, line N\nCLASS
  /// (ADDRESS): MESSAGE"): MESSAGE alone, on one line; empty for the
  /// pipeline's failure reports.
  static std::string Message(const char* text);

protected:
  BrumeOutputWindow() = default;
  ~BrumeOutputWindow() override = default;

private:
  BrumeOutputWindow(const BrumeOutputWindow&) = delete;
  void operator=(const BrumeOutputWindow&) = delete;
};

#endif
