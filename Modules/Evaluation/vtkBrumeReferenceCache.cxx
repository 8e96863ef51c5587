// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeReferenceCache.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkCamera.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <system_error>

vtkStandardNewMacro(vtkBrumeReferenceCache);

namespace
{
// The scene key as a safe file-name part.
std::string FileNamePart(const char* key)
{
  std::string part = key && *key ? key : "scene";
  for (char& c : part)
  {
    const bool safe =
      std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    c = safe ? c : '-';
  }
  return part;
}

// The cached image when `path` holds one with radiance, else null.
vtkSmartPointer<vtkImageData> ReadCached(const std::filesystem::path& path)
{
  std::error_code error;
  if (!std::filesystem::exists(path, error))
  {
    return nullptr;
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  if (!reader->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Radiance))
  {
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  return image;
}
}

vtkBrumeReferenceCache::vtkBrumeReferenceCache()
{
  this->SetSceneKey("scene");
}

vtkBrumeReferenceCache::~vtkBrumeReferenceCache()
{
  this->SetCacheDirectory(nullptr);
  this->SetSceneKey(nullptr);
}

int vtkBrumeReferenceCache::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* scene = vtkDataObject::GetData(inputVector[0], 0);
  auto* output = vtkImageData::GetData(outputVector, 0);
  const int w = this->Size[0], h = this->Size[1];
  this->FileName.clear();
  this->ReadFromCache = false;
  this->RenderSeconds = 0;

  std::filesystem::path cached;
  if (this->CacheDirectory && *this->CacheDirectory)
  {
    std::ostringstream key;
    key << FileNamePart(this->SceneKey) << "-" << w << "x" << h << "-spp" << this->SamplesPerPixel
        << "-seed" << this->Seed << "-v1";
    cached =
      std::filesystem::path(this->CacheDirectory) / ("brume-reference-" + key.str() + ".vti");
    this->FileName = cached.string();
    if (const auto image = ReadCached(cached))
    {
      int dims[3];
      image->GetDimensions(dims);
      if (dims[0] == w && dims[1] == h)
      {
        output->ShallowCopy(image);
        this->ReadFromCache = true;
        return 1;
      }
    }
  }

  vtkNew<vtkBrumeReferencePathTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetCamera(vtkBrumeEvaluationView::Camera(scene, this->Camera));
  tracer->SetSize(w, h);
  tracer->SetSamplesPerPixel(this->SamplesPerPixel);
  tracer->SetSeed(this->Seed);
  const auto start = std::chrono::steady_clock::now();
  if (!tracer->GetExecutive()->Update())
  {
    vtkErrorMacro("The reference path tracer failed (see the error above).");
    return 0;
  }
  this->RenderSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  output->ShallowCopy(tracer->GetOutput());
  if (cached.empty())
  {
    return 1;
  }
  std::error_code error;
  std::filesystem::create_directories(cached.parent_path(), error);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(this->FileName.c_str());
  writer->SetInputData(output);
  writer->SetDataModeToBinary(); // inline: VTK 9.2 misreads appended data under expat 2.5
  if (error || !writer->Write())
  {
    vtkWarningMacro("Could not keep the reference in " << this->FileName << ".");
  }
  return 1;
}

void vtkBrumeReferenceCache::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "CacheDirectory: " << (this->CacheDirectory ? this->CacheDirectory : "") << "\n";
  os << indent << "SceneKey: " << (this->SceneKey ? this->SceneKey : "") << "\n";
}
