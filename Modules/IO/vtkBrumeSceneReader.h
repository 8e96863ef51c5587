// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSceneReader
 * @brief   reads a Brume scene file (versioned JSON) into a scene collection
 *
 * The format is documented in Data/scenes/README.md and its JSON schema in
 * Data/scenes/brume-scene.schema.json. Surfaces name geometry files read by
 * VTK's readers (.obj, .ply, .stl, .vtp, .vtu) or give quads inline; media
 * are boxes, optionally with a density from an OpenVDB grid (used sparsely,
 * in place) or a .vti array; lights, camera and render settings complete it.
 * File paths are relative to the scene file.
 *
 * The output is a vtkPartitionedDataSetCollection as vtkBrumeSceneConversion
 * describes, with the lights, camera and render settings in its field data
 * (`BrumeLight*`, `BrumeCamera*`, `BrumeRender*`).
 *
 * A medium whose density is a list of files (`"vti": [...]` or `"vdb":
 * [...]`, with optional `"times"`) changes over time: the output information
 * announces the scene's time steps (TIME_STEPS, TIME_RANGE: every such
 * list's times merged), and each execution reads the step at the time
 * asked for (UPDATE_TIME_STEP: the last step at or before it). Meshes and
 * densities that do not change are read once and handed out again while
 * their files keep their size and modification time, so a new time step
 * reads only the steps' files, and downstream filters find the same arrays.
 *
 * Every value is checked before anything is read or allocated: a malformed
 * file, an unknown key, a missing file, a NaN, Inf or negative coefficient,
 * |g| >= 1 or an absurd size gives an error naming the file and the field.
 *
 * @sa vtkBrumeSceneWriter vtkBrumeLightTracer
 */
#ifndef vtkBrumeSceneReader_h
#define vtkBrumeSceneReader_h

#include "vtkBrumeIOModule.h" // For export macro
#include "vtkPartitionedDataSetCollectionAlgorithm.h"

#include <memory> // For the cache
#include <string> // For FileName
#include <vector> // For TimeSteps

class vtkBrumeSceneFileCache;

class VTKBRUMEIO_EXPORT vtkBrumeSceneReader : public vtkPartitionedDataSetCollectionAlgorithm
{
public:
  static vtkBrumeSceneReader* New();
  vtkTypeMacro(vtkBrumeSceneReader, vtkPartitionedDataSetCollectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scene file.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// The format version this reader writes and reads.
  static constexpr int FormatVersion = 1;

  /**
   * 1 when `fileName` looks like a Brume scene file: its first 4 KiB name
   * the "brume_scene" key (ParaView's reader factory asks, so that other
   * JSON files are not offered to this reader); 0 otherwise.
   */
  static int CanReadFile(const char* fileName);

  /// Files (meshes and .vti densities) read from disk by this reader since
  /// it was made, not found kept from an execution before.
  vtkTypeUInt64 GetNumberOfFileReads() const;

protected:
  vtkBrumeSceneReader();
  ~vtkBrumeSceneReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  // The file's document, parsed once per version of the file: false with
  // `error` set when it cannot be read.
  bool ReadDocument(std::string& error);

  struct Document;
  std::unique_ptr<Document> Doc;
  std::unique_ptr<vtkBrumeSceneFileCache> Cache;

  vtkBrumeSceneReader(const vtkBrumeSceneReader&) = delete;
  void operator=(const vtkBrumeSceneReader&) = delete;
};

#endif
