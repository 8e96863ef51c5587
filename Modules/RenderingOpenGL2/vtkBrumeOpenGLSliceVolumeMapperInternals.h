// SPDX-License-Identifier: BSD-3-Clause
// The OpenGL slice mapper's state (private to Brume::RenderingOpenGL2):
// its textures and what they were made from, shared by the drawing
// (vtkBrumeOpenGLSliceVolumeMapper.cxx) and the texture uploads
// (vtkBrumeOpenGLSliceVolumeMapperTextures.cxx).
#ifndef vtkBrumeOpenGLSliceVolumeMapperInternals_h
#define vtkBrumeOpenGLSliceVolumeMapperInternals_h

#include "vtkBrumeOpenGLSliceVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtkWeakPointer.h"

#include <memory>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;

struct vtkBrumeOpenGLSliceVolumeMapper::Internals
{
  // Consecutive slices of one volume and spacing, drawn by one call.
  struct Run
  {
    vtkBrumeOpenGLSliceVolumeMapper* Owner;
    float Spacing;
    int FirstVertex, Vertices;
  };

  vtkNew<vtkTextureObject> Source;
  vtkNew<vtkTextureObject> Extinction; // RGB per cell, or a sparse grid's atlas of bricks
  // A sparse extinction grid: per brick, the atlas texel of its slot (xyz,
  // w = 1) or its one value (x, w = -1); the grid's cells, bricks and atlas
  // size, and the extinction per unit of its values.
  vtkNew<vtkTextureObject> BrickTable;
  bool Bricked = false;
  // A homogeneous medium's one extinction (every cell alike): a uniform, no
  // texture read per fragment.
  bool ConstantExtinction = false;
  float Constant[3] = { 0.f, 0.f, 0.f };
  float GridCells[3] = { 1.f, 1.f, 1.f };
  float BrickCount[3] = { 1.f, 1.f, 1.f };
  float AtlasSize[3] = { 1.f, 1.f, 1.f };
  // Per slot of the atlas, the value of a texel t: SlotValue[0] t +
  // SlotValue[1] (a 16-bit normalized texture holds the grid's integers
  // less their least, or the slot's floats over their interval; floats are
  // themselves: 1 and 0). Kept with the atlas.
  std::vector<float> SlotValue;
  int AtlasBytes = 0; // per texel
  // Half the quantum of 16-bit floats (0: exact) and the bound in optical
  // depth it makes under the current function.
  double AtlasHalfQuantum = 0.0;
  double AtlasDepthError = 0.0;
  // What the atlas holds: the arrays it was filled from (their memory kept
  // alive, so that the same memory is the same samples; a reconstruction
  // that keeps a grid after an edit of a transfer function hands the same
  // memory again), its filter, and the largest stored sample.
  vtkSmartPointer<vtkDataArray> AtlasSamples;
  vtkSmartPointer<vtkDataArray> AtlasSlots;
  int AtlasFilter = -1;
  double AtlasLargest = 0.0;
  int AtlasUploads = 0;
  // Per slot of the atlas, the least and largest of its scalars, which a
  // transfer function bends within (a brick whose samples' interval holds
  // one of the function's kinks); kept with the atlas for the next function.
  std::vector<float> SlotLow, SlotHigh;
  std::vector<float> SlotSteep; // the largest step between neighbouring samples
  int BendingBricks = 0;
  // Per brick, which of its 4^3 parts of 2^3 cells bend (a bit each, four
  // floats of 16 bits; uploaded where a brick bends), and how many do.
  vtkNew<vtkTextureObject> BendMask;
  vtkIdType BendingParts = 0;
  float BrickScale[3] = { 1.f, 1.f, 1.f };
  // Bricks of scalars a transfer function classifies: its extinction in one
  // row (linear filtering), over TransferRange, TransferSamples wide.
  bool Classified = false;
  vtkNew<vtkTextureObject> TransferTable;
  float TransferRange[2] = { 0.f, 1.f };
  float TransferSamples = 2.f;
  // The table's green, blue and alpha hold the albedo of a medium whose
  // albedo varies (AlbedoTransferFunction): the source texture then holds
  // X, the radiance of an albedo of 1, drawn as sigma_t a X with the
  // extinction sigma_t (1 - a ForwardFraction) (BrumeForwardFraction).
  bool Albedo = false;
  float ForwardFraction = 0.f;
  // The largest sigma_t of the extinction grid of its own (any channel),
  // which bounds the slices' spacing (CutSlices).
  double MaxExtinction = 0.0;
  // Directional radiance: the coefficients (RGBA float 3D textures), the
  // order (0: none), g, and the eye and box in data coordinates.
  std::vector<vtkSmartPointer<vtkTextureObject>> Coefficients;
  int Order = 0;
  int FragmentOrder = 0;     // the order the shader evaluates (0: none)
  std::vector<float> Voxels; // per-voxel evaluation: the J-scaled coefficients
  float EvaluatedEye[3] = { 0.f, 0.f, 0.f };
  float G = 0.f;
  float EyeData[3] = { 0.f, 0.f, 0.f };
  float BoundsLower[3] = { 0.f, 0.f, 0.f };
  float BoundsExtent[3] = { 1.f, 1.f, 1.f };
  // From the input's texture coordinates to the extinction grid's (whose
  // box may be larger): scale, then offset.
  float ExtinctionScale[3] = { 1.f, 1.f, 1.f };
  float ExtinctionOffset[3] = { 0.f, 0.f, 0.f };
  // sigma_t's factor for a forward peak drawn as transport (field data
  // BrumeExtinctionFactor; 1 without).
  float ExtinctionFactor[3] = { 1.f, 1.f, 1.f };
  // The rows of the map from world to texture coordinates (the model's
  // inverse over the box's extent), and the extinction samples a slab
  // takes along each ray (CutSlices: one per cell of an extinction grid
  // of its own the slices' spacing spans, at most MaxSlabSamples).
  float TextureFromWorld[3][3] = { { 1.f, 0.f, 0.f }, { 0.f, 1.f, 0.f }, { 0.f, 0.f, 1.f } };
  int SlabSamples = 1;
  // Whether the slabs may take samples along the rays (still frames): a
  // classified grid's bending bricks then take four for each.
  bool SlabsWanted = false;
  // Parts each sample takes in bricks the transfer function bends within:
  // four samples a fine cell.
  int BendParts = 1;
  vtkTimeStamp TextureTime;
  std::vector<float> SourceValues; // RGBA per cell, reused from one upload to the next
  std::vector<float> Scratch;      // the input's extinction, likewise
  // The input's extinction last uploaded (RGBA per cell; empty when the
  // extinction is a grid of its own).
  std::vector<float> ExtinctionValues;
  vtkWeakPointer<vtkDataArray> ExtinctionArray; // and the array they came from, unmodified since
  vtkMTimeType ExtinctionArrayTime = 0;
  bool SourceIsRadiance = false; // the source texture holds S (extinction of its own)
  // The extinction grid of its own last uploaded, and when.
  vtkImageData* ExtinctionGrid = nullptr;
  vtkTimeStamp ExtinctionTime;
  int ExtinctionInterpolation = -1;
  int Interpolation = -1;
  vtkOpenGLRenderWindow* Context = nullptr;
  // The leader's buffers for all volumes of the renderer.
  vtkNew<vtkOpenGLVertexArrayObject> VAO;
  vtkNew<vtkOpenGLBufferObject> VBO;
  std::vector<float> Collected; // x, y, z (world), s, t, r (texture) per vertex
  std::vector<float> Sorted;
  std::vector<Run> Runs;

  // Whether the extinction drawn is alike in the three channels, factor
  // included: only such media can be drawn at a reduced resolution (their
  // transmittance is one number a pixel).
  bool ExtinctionGrey = true;
  bool GreyExtinction() const
  {
    return this->ExtinctionGrey && this->ExtinctionFactor[0] == this->ExtinctionFactor[1] &&
      this->ExtinctionFactor[1] == this->ExtinctionFactor[2] &&
      !(this->Albedo && this->ForwardFraction > 0.f);
  }
  // The leader's reduced resolution (vtkBrumeOpenGLSliceVolumeMapperReduced.cxx):
  // the window's depth, the coarse buffer (radiance and transmittance) and
  // its depth, and the two full-screen passes.
  vtkNew<vtkTextureObject> FullDepth;
  vtkNew<vtkTextureObject> CoarseDepth;
  vtkNew<vtkTextureObject> CoarseMedia;
  vtkNew<vtkOpenGLFramebufferObject> CoarseFramebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> CoarseDepthPass;
  std::unique_ptr<vtkOpenGLQuadHelper> UpsamplePass;
  bool ReducedFailed = false; // once the context could not: full resolution from then on
};

#endif
