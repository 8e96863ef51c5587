// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneReader.h"

#include "vtkBrumeQuotes.h"

#include "vtkBrumeSceneFileCache.h"
#include "vtkBrumeSceneFileParser.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "brume/Scene.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

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

struct vtkBrumeSceneReader::Document
{
  std::string FileName;
  std::filesystem::file_time_type Time;
  std::uintmax_t Size = 0;
  json Root;
};

vtkBrumeSceneReader::vtkBrumeSceneReader()
  : Cache(new vtkBrumeSceneFileCache)
{
  this->SetNumberOfInputPorts(0);
}

vtkBrumeSceneReader::~vtkBrumeSceneReader() = default;

vtkTypeUInt64 vtkBrumeSceneReader::GetNumberOfFileReads() const
{
  return this->Cache->GetReads();
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

bool vtkBrumeSceneReader::ReadDocument(std::string& error)
{
  const std::filesystem::path path(this->FileName);
  std::error_code stat;
  const auto time = std::filesystem::last_write_time(path, stat);
  const std::uintmax_t size = stat ? 0 : std::filesystem::file_size(path, stat);
  if (this->Doc && !stat && this->Doc->FileName == this->FileName && this->Doc->Time == time &&
    this->Doc->Size == size)
  {
    return true;
  }
  this->Doc.reset();
  std::ifstream in(path);
  if (this->FileName.empty() || !in)
  {
    error = "Cannot open the scene file '" + this->FileName + "'.";
    return false;
  }
  ObjectCounter counter;
  json::sax_parse(in, &counter);
  if (!counter.Overflow.empty())
  {
    error = vtkBrumeBoundQuotes(this->FileName + ": " + counter.Overflow + ": the scene has " +
      std::to_string(counter.Count) +
      " objects and lights so far: a scene holds at most 65,535 together");
    return false;
  }
  in.clear();
  in.seekg(0);
  std::unique_ptr<Document> doc(new Document);
  try
  {
    doc->Root = json::parse(in);
  }
  catch (const std::exception& e)
  {
    error = vtkBrumeBoundQuotes(this->FileName + ": not valid JSON: " + e.what());
    return false;
  }
  doc->FileName = this->FileName;
  doc->Time = time;
  doc->Size = size;
  this->Doc = std::move(doc);
  return true;
}

int vtkBrumeSceneReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // A scene is replicated, not split: every piece (every process of a
  // distributed run) gets all of it.
  outInfo->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  // The time steps of the media given as lists of files. A file that
  // cannot be read announces none: RequestData says what is wrong.
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  std::string error;
  const std::vector<double> times = this->ReadDocument(error)
    ? vtkBrumeSceneFileParser::TimeSteps(this->Doc->Root)
    : std::vector<double>();
  if (!times.empty())
  {
    outInfo->Set(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { times.front(), times.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkBrumeSceneReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  std::string error;
  if (!this->ReadDocument(error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  vtkNew<vtkPartitionedDataSetCollection> scene;
  vtkBrumeSceneFileParser parser(this->FileName);
  parser.SetCache(this->Cache.get());
  const bool stepped = outInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  // No time asked for: the first step, as the parser reads it.
  double time = stepped ? outInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[0] : 0.0;
  if (stepped && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    time = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    parser.SetTime(time);
  }
  this->Cache->BeginParse();
  const bool parsed = parser.Parse(this->Doc->Root, scene);
  this->Cache->EndParse();
  if (!parsed)
  {
    vtkErrorMacro(<< vtkBrumeBoundQuotes(parser.GetError()));
    return 0;
  }
  output->ShallowCopy(scene);
  if (stepped)
  {
    // The step read: the last announced time at or before the one asked for.
    const double* steps = outInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    const int n = outInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    double step = steps[0];
    for (int k = 1; k < n && steps[k] <= time; ++k)
    {
      step = steps[k];
    }
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), step);
  }
  return 1;
}

void vtkBrumeSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
