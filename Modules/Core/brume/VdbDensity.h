// SPDX-License-Identifier: BSD-3-Clause
// Density from an OpenVDB FloatGrid, used sparsely: no dense copy is made;
// majorants are kept per 8^3 block of active voxels.
#ifndef brume_VdbDensity_h
#define brume_VdbDensity_h

#include "brume/Density.h"

#include <memory>
#include <string>
#include <vector>

namespace brume
{

class VdbDensity : public DensityField
{
public:
  /**
   * Loads grid `gridName` (the first float grid when empty) from a .vdb file.
   * Returns nullptr and sets `error` when the file cannot be read, has no such
   * float grid, no active voxels, negative or non-finite values, or a
   * transform that is not an axis-aligned scale and translation.
   */
  static std::shared_ptr<VdbDensity> Load(const std::string& fileName, const std::string& gridName,
    std::string& error, const ParallelFor& parallelFor = SerialFor());
  /**
   * The same for a grid of scalars a transfer function classifies
   * (ClassifiedDensity): any finite values and background, and the value
   * ranges of its blocks. The majorants (and ranges) are found leaf by
   * leaf on `parallelFor`: the same whatever the threads.
   */
  static std::shared_ptr<VdbDensity> LoadScalars(const std::string& fileName,
    const std::string& gridName, std::string& error, const ParallelFor& parallelFor = SerialFor());
  bool ValueRanges(std::vector<float>& lo, std::vector<float>& hi) const override;

  ~VdbDensity() override;
  float Evaluate(const Vec3& p) const override;
  /// The voxels of the grid across its (widened) active box.
  std::array<int, 3> NativeResolution() const override;
  Box NativeBox() const override;
  /// The voxels' values: Evaluate() is OpenVDB's trilinear sampler between them.
  bool NativePoints(
    const std::array<int, 3>& lower, const std::array<int, 3>& count, float* out) const override;
  /// The voxel at native cell (i, j, k)'s centre, read from its leaf: the
  /// value Evaluate() interpolates there, without eight reads.
  float NativeValue(int i, int j, int k, const Vec3& centre) const override;
  /// Active voxels of the grid.
  std::size_t GetNumberOfActiveVoxels() const;

private:
  VdbDensity();
  static std::shared_ptr<VdbDensity> LoadGrid(const std::string& fileName,
    const std::string& gridName, bool scalars, std::string& error, const ParallelFor& parallelFor);
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

/// Checks the structure of a .vdb file before OpenVDB reads it: the header,
/// the file and grid metadata, the grid descriptors and the transform's name. OpenVDB trusts the
/// lengths and counts it reads, so a corrupt file of a kilobyte can make it allocate gigabytes;
/// every such length must fit in the bytes the file has. Empty when plausible.
std::string CheckVdbFile(const std::string& fileName);

/// A library's exception text made fit for a message: printable characters,
/// runs of blanks collapsed, at most 200 characters (a corrupt file can make
/// OpenVDB quote a string of hundreds of megabytes).
std::string ShortMessage(const char* what);

} // namespace brume

#endif
