// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeErrorPlot.h"

#include "vtkAutoInit.h"
#include "vtkAxis.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPNGWriter.h"
#include "vtkPlot.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkWindowToImageFilter.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

// The context device (and, through it, OpenGL and FreeType), whoever links us.
VTK_MODULE_INIT(vtkRenderingContextOpenGL2);

vtkStandardNewMacro(vtkBrumeErrorPlot);

// Curves by name: std::map draws them in name order.
struct vtkBrumeErrorPlot::vtkCurves
{
  std::map<std::string, std::vector<std::pair<double, double>>> Points;
};

vtkBrumeErrorPlot::vtkBrumeErrorPlot()
  : Curves(new vtkCurves)
{
  this->SetTitle("Brume: relative mean absolute error");
  this->SetXTitle("wall time (s)");
  this->SetYTitle("relative mean absolute error");
}

vtkBrumeErrorPlot::~vtkBrumeErrorPlot()
{
  this->SetTitle(nullptr);
  this->SetXTitle(nullptr);
  this->SetYTitle(nullptr);
}

void vtkBrumeErrorPlot::AddPoint(const char* curve, double x, double error)
{
  this->Curves->Points[curve ? curve : ""].emplace_back(x, error);
  this->Modified();
}

void vtkBrumeErrorPlot::RemoveAllCurves()
{
  this->Curves->Points.clear();
  this->Modified();
}

int vtkBrumeErrorPlot::GetNumberOfCurves()
{
  return static_cast<int>(this->Curves->Points.size());
}

bool vtkBrumeErrorPlot::Write(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    vtkErrorMacro("No file name to write the chart to.");
    return false;
  }
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(this->Size[0], this->Size[1]);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(this->Title ? this->Title : "");
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(this->XTitle ? this->XTitle : "");
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(this->YTitle ? this->YTitle : "");
  chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(this->LogX);
  chart->GetAxis(vtkAxis::LEFT)->SetLogScale(true);
  chart->SetShowLegend(true);
  const unsigned char colours[6][3] = { { 31, 119, 180 }, { 255, 127, 14 }, { 44, 160, 44 },
    { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 } };
  int k = 0;
  for (const auto& curve : this->Curves->Points)
  {
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("time");
    y->SetName(curve.first.c_str());
    for (const auto& point : curve.second)
    {
      x->InsertNextValue(point.first);
      y->InsertNextValue(point.second);
    }
    table->AddColumn(x);
    table->AddColumn(y);
    // A line needs two points; a lone point is drawn as a marker.
    vtkPlot* line = chart->AddPlot(curve.second.size() < 2 ? vtkChart::POINTS : vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    line->SetColor(colours[k % 6][0], colours[k % 6][1], colours[k % 6][2], 255);
    line->SetWidth(2.0);
    ++k;
  }
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(fileName);
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return writer->GetErrorCode() == 0;
}

void vtkBrumeErrorPlot::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Title: " << (this->Title ? this->Title : "") << "\n";
  os << indent << "XTitle: " << (this->XTitle ? this->XTitle : "") << "\n";
  os << indent << "YTitle: " << (this->YTitle ? this->YTitle : "") << "\n";
  os << indent << "LogX: " << this->LogX << "\n";
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Curves: " << this->Curves->Points.size() << "\n";
}
