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

#include <string> // For FileName

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

protected:
  vtkBrumeSceneReader();
  ~vtkBrumeSceneReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkBrumeSceneReader(const vtkBrumeSceneReader&) = delete;
  void operator=(const vtkBrumeSceneReader&) = delete;
};

#endif
