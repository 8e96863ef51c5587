// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneReader.h"

#include "vtkBrumeQuotes.h"

#include "vtkBrumeSceneFileParser.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"

#include <filesystem>
#include <fstream>

vtkStandardNewMacro(vtkBrumeSceneReader);

using json = nlohmann::json;

vtkBrumeSceneReader::vtkBrumeSceneReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkBrumeSceneReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "", std::ios::binary);
  if (!in)
  {
    return 0;
  }
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("\"brume_scene\"") != std::string::npos ? 1 : 0;
}

int vtkBrumeSceneReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // A scene is replicated, not split: every piece (every process of a
  // distributed run) gets all of it.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkBrumeSceneReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  const std::filesystem::path path(this->FileName);
  std::ifstream in(path);
  if (this->FileName.empty() || !in)
  {
    vtkErrorMacro("Cannot open the scene file '" << this->FileName << "'.");
    return 0;
  }
  json root;
  try
  {
    root = json::parse(in);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< vtkBrumeBoundQuotes(this->FileName + ": not valid JSON: " + e.what()));
    return 0;
  }
  vtkNew<vtkPartitionedDataSetCollection> scene;
  vtkBrumeSceneFileParser parser(this->FileName);
  if (!parser.Parse(root, scene))
  {
    vtkErrorMacro(<< vtkBrumeBoundQuotes(parser.GetError()));
    return 0;
  }
  output->ShallowCopy(scene);
  return 1;
}

void vtkBrumeSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
