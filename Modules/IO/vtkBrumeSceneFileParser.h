// SPDX-License-Identifier: BSD-3-Clause
// The scene-file format (Data/scenes/README.md) read into a scene collection
// (private to Brume::IO). One method per part of the document; every error
// names the file and the field (`scene.json: media[0].g: ...`), and a scene
// is checked whole (as the tracer would check it) before it is accepted.
#ifndef vtkBrumeSceneFileParser_h
#define vtkBrumeSceneFileParser_h

#include "vtkBrumeSceneConversion.h" // For ObjectSource
#include "vtkSmartPointer.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkImageData;
class vtkPartitionedDataSetCollection;
class vtkPolyData;

class vtkBrumeSceneFileParser
{
public:
  using json = nlohmann::json;

  /// `fileName` names errors and anchors the relative paths the file gives.
  explicit vtkBrumeSceneFileParser(const std::string& fileName);
  ~vtkBrumeSceneFileParser();

  /// Fills `scene` from the document; false, with GetError() set, otherwise.
  bool Parse(const json& root, vtkPartitionedDataSetCollection* scene);

  /// `file: field: what is wrong`.
  const std::string& GetError() const;

private:
  class Parser;

  bool ParseArray(const json& root, const char* key,
    bool (vtkBrumeSceneFileParser::*parseOne)(const json&, std::size_t));
  bool ParseSurface(const json& s, std::size_t i);
  bool ParseMaterial(const json& material, const std::string& m, vtkPolyData* surface);
  bool ParseMedium(const json& m, std::size_t i);
  vtkSmartPointer<vtkImageData> ParseDensity(const json& m, const std::string& at);
  bool ParseVdb(const json& density, const std::string& at, vtkImageData* image);
  bool ParseTransferFunction(const json& function, const std::string& at, vtkImageData* image);
  // OpenVDB media given without a box take the grid's active box.
  void SetBoxesFromGrids(
    const brume::Scene& scene, const std::vector<vtkBrumeSceneConversion::ObjectSource>& sources);
  bool ParseLight(const json& l, std::size_t i);
  bool ParseCamera(const json& root);
  bool ParseRender(const json& root);
  bool CheckScene();
  std::filesystem::path Relative(const std::string& name) const;

  std::unique_ptr<Parser> P;
  std::filesystem::path Directory;
  vtkPartitionedDataSetCollection* Scene = nullptr;
  // The field each object came from (name, field), to name it in later messages.
  std::vector<std::pair<std::string, std::string>> ObjectFields;
  std::vector<vtkImageData*> BoxesFromGrids; // held by the scene
};

#endif
