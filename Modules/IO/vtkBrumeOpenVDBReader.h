// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeOpenVDBReader
 * @brief   reads a float grid of an OpenVDB file as a vtkImageData
 *
 * Outputs the grid GridName (the first float grid when empty) over its
 * active bounding box, placed by the grid's transform (an axis-aligned scale
 * and translation), as point data named after the grid, optionally sampled
 * every Downsample voxels, refusing grids whose dense copy would exceed
 * MemoryLimit. With SparseReference on, it outputs no dense copy at all:
 * only the box, with the field arrays `BrumeVDBFile` and `BrumeVDBGrid` that
 * make vtkBrumeLightTracer use the grid in place, sparsely (give the box
 * `BrumeSigmaA`, `BrumeSigmaS`, `BrumeG` to make it a medium).
 *
 * GetGridNames() lists the file's float grids after UpdateInformation().
 */
#ifndef vtkBrumeOpenVDBReader_h
#define vtkBrumeOpenVDBReader_h

#include "vtkBrumeIOModule.h" // For export macro
#include "vtkImageAlgorithm.h"
#include "vtkNew.h" // For GridNames

#include <string> // For FileName

class vtkStringArray;

class VTKBRUMEIO_EXPORT vtkBrumeOpenVDBReader : public vtkImageAlgorithm
{
public:
  static vtkBrumeOpenVDBReader* New();
  vtkTypeMacro(vtkBrumeOpenVDBReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vdb file.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The float grid to read (default: the first one).
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

  ///@{
  /// Keep every Downsample-th voxel along each axis (default 1, in [1, 64]).
  vtkSetClampMacro(Downsample, int, 1, 64);
  vtkGetMacro(Downsample, int);
  ///@}

  ///@{
  /// Largest dense copy allowed, in bytes (default 1 GiB).
  vtkSetMacro(MemoryLimit, vtkTypeInt64);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  ///@}

  ///@{
  /// Output only the box and a reference to the grid (default off).
  vtkSetMacro(SparseReference, bool);
  vtkGetMacro(SparseReference, bool);
  vtkBooleanMacro(SparseReference, bool);
  ///@}

  /// The file's float grids (after UpdateInformation()).
  vtkStringArray* GetGridNames();

protected:
  vtkBrumeOpenVDBReader();
  ~vtkBrumeOpenVDBReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string GridName;
  int Downsample = 1;
  vtkTypeInt64 MemoryLimit = vtkTypeInt64(1) << 30;
  bool SparseReference = false;
  vtkNew<vtkStringArray> GridNames;

private:
  vtkBrumeOpenVDBReader(const vtkBrumeOpenVDBReader&) = delete;
  void operator=(const vtkBrumeOpenVDBReader&) = delete;
};

#endif
