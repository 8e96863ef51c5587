// SPDX-License-Identifier: BSD-3-Clause
// The density fields vtkBrumeSceneConversion made from a scene's arrays,
// kept while their array lives. Private to Brume::Conversion.
#ifndef vtkBrumeFieldCache_h
#define vtkBrumeFieldCache_h

#include "vtkType.h"

#include "brume/Density.h"
#include "brume/TransferFunction.h"

#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

class vtkDataArray;

namespace vtkBrumeSceneConversionInternals
{
/**
 * The tracer, the reconstruction and the renderer each convert the same
 * scene, and an edit of a medium's transfer function leaves its scalars as
 * they were: a 512^3 field read, copied and ranged three times per image,
 * and again per edit. The cache keeps, per array, the grid made from it
 * (while the array's modification time and the grid's placement are the
 * same) and the grid classified by the last opacity function asked for, and
 * lets them go when the array is deleted (its DeleteEvent) or modified.
 * A grid of a float array of one component reads the array's own memory
 * (the densities handed out hold a reference to the array, the cache does
 * not); another array's grid holds one float per value as long as the
 * array lives. Thread safe.
 */
class FieldCache
{
public:
  static FieldCache& Instance();

  /// What a grid is made from: its array (by identity and modification
  /// time), the component, and how the values are placed and read.
  struct GridKey
  {
    vtkDataArray* Array;
    vtkMTimeType Time;
    int Component;
    bool Classified;
    std::array<int, 3> Dims;
    brume::Box Bounds;
    bool Cells;
    brume::GridDensity::Interpolation Interpolation;
    bool operator==(const GridKey& o) const;
  };

  using MakeGrid = std::function<std::shared_ptr<const brume::GridDensity>()>;
  /// Makes the classified scalars, given those the grid's last function
  /// classified (null where none is kept), whose work it may reuse.
  using MakeClassified = std::function<std::shared_ptr<const brume::ClassifiedDensity>(
    const brume::ClassifiedDensity* previous)>;

  /// The grid of `key`: the one kept, or make()'s (kept unless null).
  std::shared_ptr<const brume::GridDensity> Grid(const GridKey& key, const MakeGrid& make);
  /**
   * `scalars` classified by `opacity`: the one kept for a kept grid and
   * the same function, or make()'s (kept, in place of the grid's last, where
   * `scalars` is a kept grid).
   */
  std::shared_ptr<const brume::ClassifiedDensity> Classified(
    const std::shared_ptr<const brume::DensityField>& scalars,
    const brume::OpacityTransferFunction& opacity, const MakeClassified& make);

  /// The arrays whose grids are kept.
  std::size_t NumberOfKeptArrays();
  /// Lets go of everything kept for `array`.
  void Forget(vtkDataArray* array);

private:
  struct Entry
  {
    GridKey Key;
    std::shared_ptr<const brume::GridDensity> Grid;
    std::shared_ptr<const brume::ClassifiedDensity> Classified;
  };
  std::mutex Mutex;
  std::vector<Entry> Entries;
};
}

#endif
