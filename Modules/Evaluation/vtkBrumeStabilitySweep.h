// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeStabilitySweep
 * @brief   where the pipeline fails: one scene parameter at a time, on any scene
 *
 * Varies one parameter of the input scene at a time and measures, for each
 * case, the pipeline (MaxParticles particles, per-view and
 * spherical-harmonics media) and the path tracer given the pipeline's time
 * (its samples per pixel from the time of one sample) against a converged
 * reference of that case (vtkBrumeReferenceCache, ReferenceSamples samples
 * per pixel, seed Seed + 1000003). The cases, in this order:
 *
 * - `g` = -0.99, -0.5, 0, 0.5, 0.75, 0.8, 0.9, 0.95, 0.99 (the medium's
 *   BrumeG; past 0.7 the phase function's forward peak is set apart);
 * - `optical thickness` = 1.1 k for k = 0.001, 0.1, 1, 10, 100, 1000
 *   (BrumeSigmaS = k, BrumeSigmaA = 0.1 k per channel);
 * - `albedo` = a for a = 0, 0.5, 0.9, 0.99, 0.999, 1 (BrumeSigmaS = 1.1 a,
 *   BrumeSigmaA = 1.1 (1 - a));
 * - `sheet voxels` = 1, 2, 4: the medium made a sheet through its box's
 *   centre, tilted 45 degrees about y, that many cells of a 64^3 grid
 *   over the box thick, of optical depth 1 across and albedo 0.9 (a
 *   structure far thinner than the textures' texels);
 * - `particles` = max(100, MinParticles), then x10 up to MaxParticles (the
 *   scene as it is);
 * - the surface's name = `glossy` (Phong: BrumeReflectance 0.2,
 *   BrumeSpecular 0.6, BrumeExponent 50), `glossy e=1000` (the same with
 *   BrumeExponent 1000: its lobe is cast, brume::MirrorReflection) and
 *   `mirror` (BrumeReflectance 0, BrumeSpecular 0.9);
 * - `surface in medium` = 1.1 k for k = 1, 10, 100: the medium reaching
 *   through the surface (BrumeSigmaS = k, BrumeSigmaA = 0.1 k per
 *   channel), a surface lit through a dense medium and a medium cut by a
 *   surface, as fog lying on a floor or a cloud reaching into the ground.
 *   Along the axis where the surface lies beside the medium's box (the
 *   two overlapping across the other axes; the nearest, where several),
 *   the box's face nearest the surface is moved past it by a quarter of
 *   the distance from the surface to the box's far face, its density grid
 *   stretched with it; a surface that crosses the box already leaves it
 *   as it is. Skipped when the scene has no medium or no surface, or the
 *   surface lies beside the box along no axis.
 *
 * A medium read from an OpenVDB file (BrumeVDBFile) takes its box and its
 * density from the file: its sheet and surface-in-medium cases, which
 * reshape the medium's grid, are skipped.
 *
 * The medium cases edit one medium: MediumName, or when it is empty the
 * scene's first medium (its first vtkImageData object). The surface cases
 * edit one surface: SurfaceName, or when it is empty the surface that
 * covers the most pixels of the view (the physics core's ray caster casts
 * one ray through each pixel centre of a grid 128 pixels wide with the
 * image's aspect, whatever Size is, and counts the first surface each
 * meets, seen through the media; emissive surfaces are not chosen, since
 * the cases are about reflection; ties go to the first in the collection).
 * A scene without a medium skips the medium cases, one without a
 * (non-emissive) surface the surface cases: GetChosenMediumName() or
 * GetChosenSurfaceName() is then empty. A name that is not a medium (a
 * surface) of the scene is an error.
 *
 * The output is a vtkTable, one row per case: `parameter`, `value`
 * (strings), `pipeline_seconds`, `pipeline_rel_mae`, `pathtracer_spp`,
 * `pathtracer_seconds`, `pathtracer_rel_mae`, `finite` (1 when no image
 * of the case holds a NaN or an infinity), `pipeline_sh_rel_mae`, then
 * the block errors (vtkBrumeImageError) `pipeline_block_error`,
 * `pathtracer_block_error`, `pipeline_sh_block_error`, and
 * `reference_noise`: the reference's own noise as a relative MAE sees it
 * (sqrt(2/pi) times its pixels' standard errors over its mean radiance),
 * about what an image equal to the truth would score; a case whose errors
 * come near it needs a reference with more samples (ReferenceSamples).
 * Rows are appended as they are measured, each followed by a progress
 * event. With Parameter set, only that parameter's cases run (the
 * `parameter` column's value: `g`, `optical thickness`, `albedo`,
 * `sheet voxels`, `particles`, the surface's name, or `surface in
 * medium`).
 *
 * Converged references are cached under CacheKey (default: SceneName),
 * followed by `-sweep-`, the medium's name for the medium cases (the
 * medium's and the surface's, `MEDIUM through SURFACE`, for the
 * surface-in-medium cases), the parameter and the value. Needs an OpenGL context (an X display).
 *
 * @sa vtkBrumeErrorChart vtkBrumeTimedPipeline
 */
#ifndef vtkBrumeStabilitySweep_h
#define vtkBrumeStabilitySweep_h

#include "vtkBrumeEvaluationAlgorithm.h"
#include "vtkBrumeEvaluationModule.h" // For export macro

#include <string> // For the chosen names

class VTKBRUMEEVALUATION_EXPORT vtkBrumeStabilitySweep : public vtkBrumeEvaluationAlgorithm
{
public:
  static vtkBrumeStabilitySweep* New();
  vtkTypeMacro(vtkBrumeStabilitySweep, vtkBrumeEvaluationAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The medium and the surface to edit (default empty: chosen as above).
  vtkSetStringMacro(MediumName);
  vtkGetStringMacro(MediumName);
  vtkSetStringMacro(SurfaceName);
  vtkGetStringMacro(SurfaceName);
  ///@}

  ///@{
  /// Only the cases of this parameter (default empty: every case).
  vtkSetStringMacro(Parameter);
  vtkGetStringMacro(Parameter);
  ///@}

  ///@{
  /**
   * The medium and the surface the cases would edit in `scene` with the
   * current settings: their names, "" when the scene has none (the cases
   * are skipped), or nullptr, with an error, when MediumName or
   * SurfaceName names no such object or the scene is not valid. The
   * returned text lives until the next call.
   */
  const char* ChooseMedium(vtkDataObject* scene);
  const char* ChooseSurface(vtkDataObject* scene);
  ///@}

  ///@{
  /// What the last update edited ("" for skipped cases).
  const char* GetChosenMediumName() { return this->ChosenMedium.c_str(); }
  const char* GetChosenSurfaceName() { return this->ChosenSurface.c_str(); }
  ///@}

  /// True when every image of the last update was finite.
  vtkGetMacro(AllFinite, bool);

  /// Draws the last output (rel. MAE per case, three curves) into a PNG file.
  bool WriteImage(const char* fileName);

protected:
  vtkBrumeStabilitySweep();
  ~vtkBrumeStabilitySweep() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* MediumName = nullptr;
  char* SurfaceName = nullptr;
  char* Parameter = nullptr;
  bool AllFinite = true;
  std::string ChosenMedium;
  std::string ChosenSurface;

private:
  vtkBrumeStabilitySweep(const vtkBrumeStabilitySweep&) = delete;
  void operator=(const vtkBrumeStabilitySweep&) = delete;

  // Collection indices of the chosen objects (-1: none); false on error.
  bool FindMedium(vtkDataObject* scene, int& index);
  bool FindSurface(vtkDataObject* scene, int& index);
};

#endif
