// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeOpenGLSliceVolumeMapper
 * @brief   OpenGL implementation of vtkBrumeSliceVolumeMapper
 *
 * Source radiance and extinction live in two RGB float 3D textures. Each
 * frame, the first slice mapper the renderer calls composites every visible
 * volume of the renderer that uses this mapper: their slices are merged and
 * drawn far to near in one pass, with dual-source blending
 * (GL_ONE, GL_SRC1_COLOR) so that each colour channel keeps its own
 * transmittance: C = S (1 - T) + T C_behind, T = exp(-sigma_t Delta).
 *
 * @sa vtkBrumeSliceVolumeMapper
 */
#ifndef vtkBrumeOpenGLSliceVolumeMapper_h
#define vtkBrumeOpenGLSliceVolumeMapper_h

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkBrumeSliceVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <vector> // For slices

class vtkCamera;
class vtkFieldData;
class vtkImageData;
class vtkInformationIntegerKey;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolume;

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeOpenGLSliceVolumeMapper
  : public vtkBrumeSliceVolumeMapper
{
public:
  static vtkBrumeOpenGLSliceVolumeMapper* New();
  vtkTypeMacro(vtkBrumeOpenGLSliceVolumeMapper, vtkBrumeSliceVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  /**
   * The bytes per texel of the atlas of a bricked extinction grid last
   * sent to the GPU: 2 for a grid of integers spanning at most 65,535 (a
   * scan's own 8- or 16-bit values, classified by a transfer function) and
   * for floats whose 16-bit values keep within SetExtinctionDepthTolerance(),
   * 4 otherwise; 0 before any.
   */
  int GetExtinctionAtlasTexelBytes() const;
  /**
   * The bound, in optical depth along any ray across the grid, of what the
   * last atlas's 16-bit values may change from its floats (half their
   * quantum times the largest extinction per unit of value and the grid's
   * diagonal; for classified scalars, the larger of that and the albedo's
   * largest change): 0 when the atlas holds its values exactly.
   */
  double GetExtinctionAtlasDepthError() const;
  /**
   * Of the last bricked grid of classified scalars sent to the GPU, the
   * stored bricks where samples are taken four times a fine cell along the
   * rays (SetBendSampling): their scalars span a point of the transfer
   * function steeply enough that one sample a fine cell would miss their
   * classified extinction (a one-voxel sheet through a step of the
   * function: -21 % to +51 % of its optical depth, by where the samples
   * fall; within 1.5 % with four).
   */
  int GetNumberOfBendingBricks() const;
  /**
   * Of those bricks' parts (4^3 a brick, 2^3 cells each: the samples that
   * their own points interpolate), the ones sampled finer: a bending
   * brick's parts that do not hold the steep crossing (the fog beside a
   * sheet) keep one sample a fine cell.
   */
  vtkIdType GetNumberOfBendingParts() const;
  /**
   * How many times the atlas of a bricked grid was filled. A grid of the
   * same samples as the atlas holds (the same memory: a reconstruction
   * that kept the scalars' bricks after an edit of a transfer function)
   * is not sent again; its brick table and transfer function are.
   */
  int GetNumberOfExtinctionAtlasUploads() const;

  /// Renderer keys: the frame count and the frame whose volumes were drawn.
  static vtkInformationIntegerKey* FRAME();
  /**
   * The bytes of memory the GPU of `window` reports free: the current
   * available video memory of GL_NVX_gpu_memory_info (NVIDIA), or the free
   * texture memory of GL_ATI_meminfo (AMD); -1 where its driver has
   * neither (Mesa's llvmpipe and OSMesa among them) or the window has no
   * OpenGL context yet (before its first render). Makes the context
   * current. The mapper asks it before it makes an atlas: one that does
   * not fit fails with a message instead of the driver's out-of-memory.
   */
  static vtkTypeInt64 GetFreeGPUMemory(vtkRenderWindow* window);
  static vtkInformationIntegerKey* DRAWN_FRAME();

protected:
  vtkBrumeOpenGLSliceVolumeMapper();
  ~vtkBrumeOpenGLSliceVolumeMapper() override;

private:
  vtkBrumeOpenGLSliceVolumeMapper(const vtkBrumeOpenGLSliceVolumeMapper&) = delete;
  void operator=(const vtkBrumeOpenGLSliceVolumeMapper&) = delete;

  struct Slice;
  /// Uploads the textures if needed and appends this volume's slices.
  bool PrepareSlices(vtkRenderer* ren, vtkVolume* vol, std::vector<Slice>& slices);
  // The steps of PrepareSlices: the textures (when the input changed), the
  // directional radiance, its evaluation toward the eye, the slice polygons.
  bool UploadTextures(
    vtkImageData* input, vtkOpenGLRenderWindow* renWin, const int dims[3], int interpolation);
  bool UploadExtinction(vtkOpenGLRenderWindow* renWin, int filter);
  // The input's own extinction (RGBA per cell), unless unchanged.
  bool UploadInputExtinction(
    vtkOpenGLRenderWindow* renWin, const int dims[3], int filter, const std::vector<float>& e);
  // UploadExtinction's two forms of the grid: dense cell values, or bricks.
  bool UploadDenseExtinction(
    vtkImageData* grid, const int dims[3], vtkOpenGLRenderWindow* renWin, int filter);
  bool UploadBricks(
    vtkImageData* grid, const int dims[3], vtkOpenGLRenderWindow* renWin, int filter);
  // The atlas's storage, `bytes` (2 or 4) per texel, its texels left to the caller.
  bool CreateAtlas(vtkOpenGLRenderWindow* renWin, const int texels[3], int bytes, int filter);
  bool UploadTransferFunction(vtkFieldData* fd, vtkOpenGLRenderWindow* renWin, double& largest);
  bool UploadDirectional(vtkImageData* input, vtkOpenGLRenderWindow* renWin, const int dims[3],
    int filter, const std::vector<float>& extinction);
  bool EvaluateTowardEye(vtkOpenGLRenderWindow* renWin, const int dims[3], int interpolation);
  void CutSlices(
    vtkCamera* camera, vtkMatrix4x4* model, vtkImageData* input, std::vector<Slice>& slices);
  /// Draws the slices of every slice volume of the renderer.
  void DrawAll(vtkRenderer* ren);
  /// Draws DrawAll's slices, into the window or (`reduced`) a coarse buffer.
  void DrawRuns(vtkRenderer* ren, bool reduced);
  /**
   * Draws DrawAll's slices (of `volumes`) into a buffer `distance` times
   * coarser, then upsamples it over the window with the window's depth,
   * both within the volumes' rectangle on screen; false, with nothing
   * drawn, where the context cannot.
   */
  bool DrawReduced(vtkRenderer* ren, double distance, const std::vector<vtkVolume*>& volumes);
  // DrawReduced's steps: the warning that sends the media to full
  // resolution from then on (false), the slices drawn into the coarse
  // buffer (false after that warning), and the coarse buffer upsampled over
  // the window.
  struct ReducedLayout;
  bool FailReduced(const char* what);
  bool DrawCoarse(vtkRenderer* ren, const ReducedLayout& layout);
  void Upsample(vtkRenderer* ren, const ReducedLayout& layout);

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
