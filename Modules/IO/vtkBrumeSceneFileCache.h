// SPDX-License-Identifier: BSD-3-Clause
// The data a scene file's surfaces and densities were read into, kept by
// vtkBrumeSceneReader from one execution to the next (private to
// Brume::IO). A scene that changes over time reads only what changed at
// each step: a mesh or a constant density is read once and handed out
// again while its file keeps its size and modification time, so the
// arrays downstream (the conversion's grids, keyed by array) are the same
// objects from step to step. What a parse did not use is let go.
#ifndef vtkBrumeSceneFileCache_h
#define vtkBrumeSceneFileCache_h

#include "vtkDataObject.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace brume
{
class DensityField;
}

class vtkBrumeSceneFileCache
{
public:
  /// The data kept for `file` (as `kind` read it: "mesh", "vti:ARRAYS"...),
  /// or null when none is, or the file changed since.
  vtkDataObject* Find(const std::filesystem::path& file, const std::string& kind);
  /// Keeps `data`, read from `file` as `kind`.
  void Keep(const std::filesystem::path& file, const std::string& kind, vtkDataObject* data);
  /// Starts a parse: what it does not Find or Keep is let go at EndParse().
  void BeginParse();
  void EndParse();
  /// Files read from disk (not found kept) since the cache was made.
  std::uint64_t GetReads() const { return this->Reads; }
  /// The densities the last parse's check of its scene made (an OpenVDB
  /// grid read, its majorants built), held until the next parse's: the
  /// tracer's conversion finds the same grid (vtkBrumeSceneConversion keeps
  /// one while someone holds it) instead of reading its file again.
  void KeepDensities(std::vector<std::shared_ptr<const brume::DensityField>> densities)
  {
    this->Densities = std::move(densities);
  }

private:
  struct Entry
  {
    std::filesystem::file_time_type Time;
    std::uintmax_t Size = 0;
    vtkSmartPointer<vtkDataObject> Data;
    bool Used = false;
  };
  static bool Stamp(
    const std::filesystem::path& file, std::filesystem::file_time_type& time, std::uintmax_t& size);
  std::map<std::pair<std::string, std::string>, Entry> Entries;
  std::uint64_t Reads = 0;
  std::vector<std::shared_ptr<const brume::DensityField>> Densities;
};

#endif
