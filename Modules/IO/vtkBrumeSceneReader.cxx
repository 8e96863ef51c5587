// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneReader.h"

#include "vtkBrumeQuotes.h"

#include "vtkBrumeSceneFileParser.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"

#include "brume/Scene.h"

#include <filesystem>
#include <fstream>
#include <string>

vtkStandardNewMacro(vtkBrumeSceneReader);

using json = nlohmann::json;

namespace
{
// Counts the elements of the top-level arrays "surfaces", "media" and
// "lights" as the file is read, without building its document, and stops
// at the element that makes them more than a scene holds: a file of a
// million lights is refused after reading 65,536 of them, not after its
// whole document is built (3 s and 745 MB for 60 MB of JSON).
class ObjectCounter : public nlohmann::json_sax<json>
{
public:
  std::size_t Count = 0;
  std::string Overflow; // the array whose element overflowed, "" if none

  bool null() override { return this->Element(); }
  bool boolean(bool) override { return this->Element(); }
  bool number_integer(number_integer_t) override { return this->Element(); }
  bool number_unsigned(number_unsigned_t) override { return this->Element(); }
  bool number_float(number_float_t, const string_t&) override { return this->Element(); }
  bool string(string_t&) override { return this->Element(); }
  bool binary(binary_t&) override { return this->Element(); }
  bool key(string_t& key) override
  {
    if (this->Depth == 1)
    {
      this->Key = key;
    }
    return true;
  }
  bool start_object(std::size_t) override
  {
    const bool go = this->Element();
    ++this->Depth;
    return go;
  }
  bool end_object() override
  {
    --this->Depth;
    return true;
  }
  bool start_array(std::size_t) override
  {
    const bool go = this->Element();
    if (this->Depth == 1 &&
      (this->Key == "surfaces" || this->Key == "media" || this->Key == "lights"))
    {
      this->Array = this->Key;
    }
    ++this->Depth;
    return go;
  }
  bool end_array() override
  {
    if (--this->Depth == 1)
    {
      this->Array.clear();
    }
    return true;
  }
  // A file that is not JSON is the document parser's to report.
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override
  {
    return false;
  }

private:
  int Depth = 0;     // objects and arrays open
  std::string Key;   // the top-level key last read
  std::string Array; // the counted top-level array open, if any

  bool Element()
  {
    if (this->Depth == 2 && !this->Array.empty() &&
      ++this->Count > brume::Scene::MaxObjectsAndLights)
    {
      this->Overflow = this->Array;
      return false;
    }
    return true;
  }
};
}

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
  ObjectCounter counter;
  json::sax_parse(in, &counter);
  if (!counter.Overflow.empty())
  {
    vtkErrorMacro(<< vtkBrumeBoundQuotes(this->FileName + ": " + counter.Overflow +
                    ": the scene has " + std::to_string(counter.Count) +
                    " objects and lights so far: a scene holds at most 65,535 together"));
    return 0;
  }
  in.clear();
  in.seekg(0);
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
