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

class vtkBrumeSceneFileCache;
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

  /**
   * The time asked for: a density given as a list of files (time steps)
   * takes the last step whose time is at most `time` (the first when all
   * are later). Without it, every such density takes its first step.
   */
  void SetTime(double time)
  {
    this->HasTime = true;
    this->Time = time;
  }

  /// Where meshes and .vti densities are looked for before they are read,
  /// and kept once read (null: read every time).
  void SetCache(vtkBrumeSceneFileCache* cache) { this->Cache = cache; }

  /**
   * The time steps of a scene document: the times of every density given
   * as a list of files, merged and sorted (empty for a scene that does not
   * change). Lenient: a malformed list is Parse()'s to report.
   */
  static std::vector<double> TimeSteps(const json& root);

private:
  class Parser;

  bool ParseArray(const json& root, const char* key,
    bool (vtkBrumeSceneFileParser::*parseOne)(const json&, std::size_t));
  bool ParseSurface(const json& s, std::size_t i);
  bool ParseMaterial(const json& material, const std::string& m, vtkPolyData* surface);
  bool ParseMedium(const json& m, std::size_t i);
  vtkSmartPointer<vtkImageData> ParseDensity(const json& m, const std::string& at);
  bool ParseVdb(const json& density, const std::string& at, vtkImageData* image);
  // The file of `density[key]` at the time asked for, and its field.
  bool StepFile(const json& density, const std::string& key, const std::string& at,
    std::string& file, std::string& field);
  vtkSmartPointer<vtkImageData> ReadImage(
    const std::filesystem::path& file, const std::string& field);
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
  vtkBrumeSceneFileCache* Cache = nullptr;
  std::string StepField; // the step's file of the medium parsed, if a list gave it
  bool HasTime = false;
  double Time = 0.0;
};

#endif
