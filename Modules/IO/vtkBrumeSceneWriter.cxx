// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneWriter.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <filesystem>
#include <fstream>

vtkStandardNewMacro(vtkBrumeSceneWriter);

namespace
{
using json = nlohmann::json;

json Tuple(vtkDataArray* a, vtkIdType i = 0)
{
  json values = json::array();
  for (int c = 0; c < a->GetNumberOfComponents(); ++c)
  {
    values.push_back(a->GetComponent(i, c));
  }
  return values;
}

std::string StringField(vtkFieldData* fd, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name));
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

// A file name from an object name.
std::string Safe(std::string name)
{
  for (char& c : name)
  {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
    {
      c = '_';
    }
  }
  return name;
}

// A surface: its geometry in a .vtp file beside the scene file, its
// material in the document. Empty on success, otherwise the error.
std::string WriteSurface(
  vtkPolyData* surface, const std::string& name, const std::filesystem::path& path, json& s)
{
  const std::string stem = path.stem().string();
  const std::string file = stem + "-" + Safe(name) + ".vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName((path.parent_path() / file).string().c_str());
  writer->SetInputData(surface);
  writer->SetDataModeToBinary(); // inline: VTK 9.2 misreads appended data under expat 2.5
  if (!writer->Write())
  {
    return "Cannot write " + file + ".";
  }
  s["name"] = name;
  s["file"] = file;
  json material = json::object();
  vtkFieldData* fd = surface->GetFieldData();
  const std::string type = StringField(fd, vtkBrumeNames::Material);
  if (!type.empty())
  {
    material["type"] = type;
  }
  for (const auto& key : { std::make_pair("reflectance", vtkBrumeNames::Reflectance),
         std::make_pair("specular", vtkBrumeNames::Specular),
         std::make_pair("emission", vtkBrumeNames::Emission),
         std::make_pair("exponent", vtkBrumeNames::Exponent) })
  {
    if (vtkDataArray* a = fd->GetArray(key.second))
    {
      material[key.first] = a->GetNumberOfComponents() == 1 ? json(a->GetTuple1(0)) : Tuple(a);
    }
  }
  s["material"] = material;
  return {};
}

// A dense medium's scalar-opacity transfer function, if it has one.
void WriteTransferFunction(vtkFieldData* fd, json& density)
{
  vtkDataArray* points = fd->GetArray(vtkBrumeNames::ScalarOpacity);
  if (!points)
  {
    return;
  }
  json& f = density["transfer_function"];
  f["opacity"] = json::array();
  for (vtkIdType i = 0; i < points->GetNumberOfTuples(); ++i)
  {
    f["opacity"].push_back(json::array({ points->GetComponent(i, 0), points->GetComponent(i, 1) }));
  }
  if (vtkDataArray* color = fd->GetArray(vtkBrumeNames::ScalarColor))
  {
    f["color"] = json::array();
    for (vtkIdType i = 0; i < color->GetNumberOfTuples(); ++i)
    {
      f["color"].push_back(json::array({ color->GetComponent(i, 0), color->GetComponent(i, 1),
        color->GetComponent(i, 2), color->GetComponent(i, 3) }));
    }
  }
  if (vtkDataArray* unit = fd->GetArray(vtkBrumeNames::ScalarOpacityUnitDistance))
  {
    f["unit_distance"] = unit->GetTuple1(0);
  }
  const std::string interpolation = StringField(fd, vtkBrumeNames::Interpolation);
  if (!interpolation.empty())
  {
    f["interpolation"] = interpolation;
  }
  if (vtkDataArray* component = fd->GetArray(vtkBrumeNames::ScalarComponent))
  {
    density["component"] = static_cast<int>(component->GetTuple1(0));
  }
}

// A medium: its box, coefficients and density (an OpenVDB file by path, a
// dense grid in a .vti file beside the scene file).
std::string WriteMedium(
  vtkImageData* medium, const std::string& name, const std::filesystem::path& path, json& m)
{
  const std::string stem = path.stem().string();
  vtkFieldData* fd = medium->GetFieldData();
  m["name"] = name;
  for (const auto& key : { std::make_pair("sigma_a", vtkBrumeNames::SigmaA),
         std::make_pair("sigma_s", vtkBrumeNames::SigmaS) })
  {
    if (vtkDataArray* a = fd->GetArray(key.second))
    {
      m[key.first] = Tuple(a);
    }
  }
  if (vtkDataArray* g = fd->GetArray(vtkBrumeNames::G))
  {
    m["g"] = g->GetTuple1(0);
  }
  if (vtkDataArray* s = fd->GetArray(vtkBrumeNames::DensityScale))
  {
    m["density_scale"] = s->GetTuple1(0);
  }
  const std::string vdb = StringField(fd, vtkBrumeNames::VDBFile);
  const bool dense = medium->GetPointData()->GetNumberOfArrays() > 0 ||
    medium->GetCellData()->GetNumberOfArrays() > 0;
  double b[6];
  medium->GetBounds(b);
  if (!vdb.empty() || !dense)
  {
    m["box"] =
      json::array({ json::array({ b[0], b[2], b[4] }), json::array({ b[1], b[3], b[5] }) });
  }
  if (!vdb.empty())
  {
    m["density"]["vdb"] = std::filesystem::absolute(vdb).string();
    const std::string grid = StringField(fd, vtkBrumeNames::VDBGrid);
    if (!grid.empty())
    {
      m["density"]["grid"] = grid;
    }
    WriteTransferFunction(fd, m["density"]);
  }
  else if (dense)
  {
    const std::string file = stem + "-" + Safe(name) + ".vti";
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName((path.parent_path() / file).string().c_str());
    writer->SetInputData(medium);
    writer->SetDataModeToBinary(); // inline: VTK 9.2 misreads appended data under expat 2.5
    if (!writer->Write())
    {
      return "Cannot write " + file + ".";
    }
    m["density"]["vti"] = file;
    const std::string array = StringField(fd, vtkBrumeNames::DensityArray);
    if (!array.empty())
    {
      m["density"]["array"] = array;
    }
    WriteTransferFunction(fd, m["density"]);
  }
  return {};
}

// The lights of the collection's field data.
void WriteLights(vtkFieldData* fd, json& root)
{
  if (auto* types = vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::LightType)))
  {
    for (vtkIdType i = 0; i < types->GetNumberOfValues(); ++i)
    {
      json l;
      const std::string type = types->GetValue(i);
      l["type"] = type;
      if (type != "directional")
      {
        l["position"] = Tuple(fd->GetArray(vtkBrumeNames::LightPosition), i);
        l["intensity"] = Tuple(fd->GetArray(vtkBrumeNames::LightIntensity), i);
      }
      else
      {
        l["irradiance"] = Tuple(fd->GetArray(vtkBrumeNames::LightIntensity), i);
      }
      if (type != "point")
      {
        l["direction"] = Tuple(fd->GetArray(vtkBrumeNames::LightDirection), i);
      }
      if (type == "spot")
      {
        l["cone_angle"] = fd->GetArray(vtkBrumeNames::LightConeAngle)->GetTuple1(i);
      }
      root["lights"].push_back(l);
    }
  }
}

// The camera and render settings of the collection's field data.
void WriteSettings(vtkFieldData* fd, json& root)
{
  using Key = std::pair<const char*, const char*>;
  const Key camera[] = { { "position", vtkBrumeNames::CameraPosition },
    { "focal_point", vtkBrumeNames::CameraFocalPoint }, { "view_up", vtkBrumeNames::CameraViewUp },
    { "view_angle", vtkBrumeNames::CameraViewAngle } };
  for (const auto& key : camera)
  {
    if (vtkDataArray* a = fd->GetArray(key.second))
    {
      root["camera"][key.first] =
        a->GetNumberOfComponents() == 1 ? json(a->GetTuple1(0)) : Tuple(a);
    }
  }
  const Key render[] = { { "particles", vtkBrumeNames::RenderParticles },
    { "size", vtkBrumeNames::RenderSize }, { "threshold", vtkBrumeNames::RenderThreshold },
    { "seed", vtkBrumeNames::RenderSeed }, { "exposure", vtkBrumeNames::RenderExposure } };
  for (const auto& key : render)
  {
    if (vtkDataArray* a = fd->GetArray(key.second))
    {
      root["render"][key.first] =
        a->GetNumberOfComponents() == 1 ? json(a->GetTuple1(0)) : Tuple(a);
    }
  }
}
}

int vtkBrumeSceneWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPartitionedDataSetCollection");
  return 1;
}

void vtkBrumeSceneWriter::WriteData()
{
  auto* scene = vtkPartitionedDataSetCollection::SafeDownCast(this->GetInput());
  if (!scene || this->FileName.empty())
  {
    vtkErrorMacro("A scene collection and a FileName are needed.");
    this->SetErrorCode(1);
    return;
  }
  const std::filesystem::path path(this->FileName);
  json root;
  root["brume_scene"] = 1;
  root["surfaces"] = json::array();
  root["media"] = json::array();
  root["lights"] = json::array();
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = scene->GetPartitionedDataSet(i);
    vtkDataObject* object =
      pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    std::string name = "object" + std::to_string(i);
    if (scene->HasMetaData(i) && scene->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
    {
      name = scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    }
    std::string error;
    json item;
    if (auto* surface = vtkPolyData::SafeDownCast(object))
    {
      error = WriteSurface(surface, name, path, item);
      root["surfaces"].push_back(item);
    }
    else if (auto* medium = vtkImageData::SafeDownCast(object))
    {
      error = WriteMedium(medium, name, path, item);
      root["media"].push_back(item);
    }
    if (!error.empty())
    {
      vtkErrorMacro(<< error);
      this->SetErrorCode(1);
      return;
    }
  }
  WriteLights(scene->GetFieldData(), root);
  WriteSettings(scene->GetFieldData(), root);
  std::ofstream out(path);
  out << root.dump(2) << "\n";
  if (!out)
  {
    vtkErrorMacro("Cannot write " << this->FileName << ".");
    this->SetErrorCode(1);
  }
}

void vtkBrumeSceneWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
