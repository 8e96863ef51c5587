// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeDefaultSceneSource
 * @brief   the built-in Brume scene: a Cornell box around a cube of fog
 *
 * Produces, as a scene collection (see vtkBrumeSceneConversion), exactly the
 * scene Brume's images are compared on: right-handed, +y up, box of side 2
 * with its front (z = +1) open and a black background; Lambertian walls as
 * quads with inward normals (floor y = -1, ceiling y = +1 and back z = -1 of
 * reflectance 0.75, left x = -1 red (0.75, 0.25, 0.25), right x = +1 green
 * (0.25, 0.75, 0.25)); a one-sided square emitter x, z in [-0.25, 0.25] at
 * y = 0.99 facing -y with radiance 15 in each channel, black itself; a
 * homogeneous, index-matched medium filling [-0.5, 0.5]^3 with sigma_s = 1.0,
 * sigma_a = 0.1 and Henyey-Greenstein g = 0.7; a pinhole camera at (0, 0, 4)
 * looking at the origin, +y up, 40 degree field of view.
 *
 * @sa vtkBrumeLightTracer
 */
#ifndef vtkBrumeDefaultSceneSource_h
#define vtkBrumeDefaultSceneSource_h

#include "vtkBrumeTracingModule.h" // For export macro
#include "vtkPartitionedDataSetCollectionAlgorithm.h"

class VTKBRUMETRACING_EXPORT vtkBrumeDefaultSceneSource
  : public vtkPartitionedDataSetCollectionAlgorithm
{
public:
  static vtkBrumeDefaultSceneSource* New();
  vtkTypeMacro(vtkBrumeDefaultSceneSource, vtkPartitionedDataSetCollectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Include the medium (default on). Turning it off gives the same box
   * without fog, for comparisons.
   */
  vtkSetMacro(IncludeMedium, bool);
  vtkGetMacro(IncludeMedium, bool);
  vtkBooleanMacro(IncludeMedium, bool);
  ///@}

protected:
  vtkBrumeDefaultSceneSource();
  ~vtkBrumeDefaultSceneSource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool IncludeMedium = true;

private:
  vtkBrumeDefaultSceneSource(const vtkBrumeDefaultSceneSource&) = delete;
  void operator=(const vtkBrumeDefaultSceneSource&) = delete;
};

#endif
