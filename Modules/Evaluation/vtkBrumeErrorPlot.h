// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeErrorPlot
 * @brief   error curves drawn with VTK's charts into a PNG file
 *
 * Named curves of (x, error) points, drawn as lines on a vtkChartXY
 * (logarithmic error axis; logarithmic x axis unless LogX is off) with a
 * legend, off screen, and written as a PNG image. Curves are drawn in the
 * order of their names, each in the next colour of a fixed palette.
 *
 * @code
 * vtkNew<vtkBrumeErrorPlot> plot;
 * plot->SetTitle("relative MAE against time");
 * plot->AddPoint("pipeline", 0.7, 0.029);
 * plot->AddPoint("path-tracer", 4.9, 0.023);
 * plot->Write("chart.png");
 * @endcode
 *
 * Needs an OpenGL context (an X display; `xvfb-run -a` without one).
 *
 * @sa vtkBrumeErrorChart vtkBrumeStabilitySweep
 */
#ifndef vtkBrumeErrorPlot_h
#define vtkBrumeErrorPlot_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For Curves

class VTKBRUMEEVALUATION_EXPORT vtkBrumeErrorPlot : public vtkObject
{
public:
  static vtkBrumeErrorPlot* New();
  vtkTypeMacro(vtkBrumeErrorPlot, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Appends the point (x, error) to the curve `curve` (created on first use).
  void AddPoint(const char* curve, double x, double error);

  /// Removes every curve.
  void RemoveAllCurves();

  /// Number of curves.
  int GetNumberOfCurves();

  ///@{
  /// Chart title (default "Brume: relative mean absolute error").
  vtkSetStringMacro(Title);
  vtkGetStringMacro(Title);
  ///@}

  ///@{
  /// Axis titles (default "wall time (s)" and "relative mean absolute error").
  vtkSetStringMacro(XTitle);
  vtkGetStringMacro(XTitle);
  vtkSetStringMacro(YTitle);
  vtkGetStringMacro(YTitle);
  ///@}

  ///@{
  /// Logarithmic x axis (default on).
  vtkSetMacro(LogX, bool);
  vtkGetMacro(LogX, bool);
  vtkBooleanMacro(LogX, bool);
  ///@}

  ///@{
  /// Image size in pixels (default 800 x 600).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  /// Draws the curves and writes them as a PNG file; false if it could not.
  bool Write(const char* fileName);

protected:
  vtkBrumeErrorPlot();
  ~vtkBrumeErrorPlot() override;

  char* Title = nullptr;
  char* XTitle = nullptr;
  char* YTitle = nullptr;
  bool LogX = true;
  int Size[2] = { 800, 600 };

private:
  vtkBrumeErrorPlot(const vtkBrumeErrorPlot&) = delete;
  void operator=(const vtkBrumeErrorPlot&) = delete;

  struct vtkCurves;
  std::unique_ptr<vtkCurves> Curves;
};

#endif
