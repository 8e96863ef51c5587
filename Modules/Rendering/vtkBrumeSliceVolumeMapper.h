// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSliceVolumeMapper
 * @brief   renders participating media as view-aligned 3D-texture slices
 *
 * Jimenez & Pueyo (2003), section 4, after Van Gelder & Kim (1996): the
 * medium's box is cut by planes perpendicular to the view direction (the
 * slices of a cube of side the medium's diagonal, clipped to the medium),
 * drawn back to front. Each slice is a slab of thickness Delta along the
 * viewing ray that radiates the voxel's source radiance S with opacity
 * alpha = 1 - exp(-sigma_t Delta); premultiplied "over" compositing then
 * gives L = sum T_before S (1 - exp(-sigma_t Delta)) + T_total L_behind.
 * Delta is corrected per fragment for perspective (1/cos of the angle to the
 * view direction). Slices are depth tested against the opaque geometry
 * already drawn, without writing depth, and start at the near plane when the
 * camera is inside the medium.
 *
 * Input: a vtkImageData whose cells are the voxels, with cell data
 * `SourceRadiance` (3 components, W m^-2 sr^-1) and `Extinction` (1 or 3
 * equal components, m^-1), as vtkBrumeRadianceReconstruction produces.
 * The volume's vtkVolumeProperty is not used: the data are physical.
 *
 * @sa vtkBrumeRadianceReconstruction vtkBrumeSceneActors
 */
#ifndef vtkBrumeSliceVolumeMapper_h
#define vtkBrumeSliceVolumeMapper_h

#include "vtkBrumeRenderingModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr

class VTKBRUMERENDERING_EXPORT vtkBrumeSliceVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkBrumeSliceVolumeMapper* New();
  vtkTypeMacro(vtkBrumeSliceVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Distance between slices along the view direction, in world units.
   * 0 (the default) uses half the smallest voxel spacing. Negative values
   * are an error.
   */
  vtkSetMacro(SliceSpacing, double);
  vtkGetMacro(SliceSpacing, double);
  ///@}

  /// Number of slices drawn by the last render.
  vtkGetMacro(LastNumberOfSlices, int);

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkBrumeSliceVolumeMapper();
  ~vtkBrumeSliceVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  double SliceSpacing = 0.0;
  int LastNumberOfSlices = 0;

private:
  vtkBrumeSliceVolumeMapper(const vtkBrumeSliceVolumeMapper&) = delete;
  void operator=(const vtkBrumeSliceVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
