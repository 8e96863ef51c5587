// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneGeometry.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeSceneFileChecks.h"
#include "vtkBrumeXMLReaders.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkExecutive.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"
#include "vtkXMLUnstructuredDataReader.h"

namespace
{
// Runs `f` with VTK's error and warning display off (readers report through
// errors that the caller turns into one message).
template <typename F>
auto Quietly(F&& f)
{
  const bool display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  auto result = f();
  vtkObject::SetGlobalWarningDisplay(display);
  return result;
}

}

vtkSmartPointer<vtkPolyData> vtkBrumeSceneGeometry::Read(
  const std::filesystem::path& file, std::string& error)
{
  const std::string ext = file.extension().string();
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".obj")
  {
    if (!vtkBrumeSceneFileChecks::Obj(file, error))
    {
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".ply")
  {
    if (!vtkBrumeSceneFileChecks::Ply(file, error))
    {
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".stl")
  {
    if (!vtkBrumeSceneFileChecks::Stl(file, error))
    {
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkBrumeXMLPolyDataReader>::New();
    r->SetFileName(file.string().c_str());
    if (!Quietly([&] { return vtkBrumeSceneFileChecks::VtkXml(r, file, error); }))
    {
      return nullptr;
    }
    reader = r;
  }
  else if (ext == ".vtu")
  {
    auto r = vtkSmartPointer<vtkBrumeXMLUnstructuredGridReader>::New();
    r->SetFileName(file.string().c_str());
    if (!Quietly([&] { return vtkBrumeSceneFileChecks::VtkXml(r, file, error); }))
    {
      return nullptr;
    }
    auto surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
    surface->SetInputConnection(r->GetOutputPort());
    reader = surface;
  }
  else
  {
    error = "unsupported geometry file type '" + ext + "' (.obj, .ply, .stl, .vtp, .vtu)";
    return nullptr;
  }
  // Readers report problems through errors, not return values: silence and check.
  const int ok =
    Quietly([&] { return reader->GetExecutive() ? reader->GetExecutive()->Update() : 0; });
  auto* output = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!ok || !output || output->GetNumberOfCells() == 0)
  {
    error = "cannot read geometry from '" + file.string() + "' (missing, corrupt or empty)";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(output);
  return copy;
}
