// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkRefractionOctree
 * @brief   the min-max octree of a refractive-index image, stored as a level per voxel
 *
 * vtkRefractionOctree computes, for an image with the point array `n_minus_1`, the min-max octree
 * of Brownlee et al. (2010, section 4.2) as one byte per voxel (schlieren::ComputeOctreeLevels):
 * level j at a voxel means that the aligned block of 2^j cells holding it, grown by a one-cell
 * halo, spans no more than Tolerance in n - 1, so a ray may cross the block in one straight step.
 * vtkSchlierenImage then steps max(base step, distance across the block) there (UseOctree on).
 *
 * The output is the input (shallow copy) with
 * - the point array `octree_level` (unsigned char; the level of the cell whose lower corner the
 *   point is; the last layer of points along each axis has no cell and holds 0),
 * - the field data `octree_tolerance` (double: the tolerance used, in n - 1 units),
 *   `octree_max_level` (double) and `octree_skippable_fraction` (double: the fraction of cells at
 *   level 1 or more, over the whole volume).
 *
 * Settings:
 * - Tolerance (n - 1 units, >= 0; default 0 = automatic): the largest spread of n - 1 a block may
 *   hold. Automatic is AutomaticToleranceFraction (1e-4) times the range of n - 1 over the whole
 *   volume (the error it costs against the fixed-step image: Testing/Python/test_accuracy.py and
 *   docs/PERFORMANCE.md). A uniform field (range 0) gets tolerance 0: every block is uniform.
 * - MaxLevel (0 to 10, default 7): blocks of at most 2^MaxLevel cells.
 *
 * Under MPI each rank computes the levels of its own piece, with the tolerance of the whole
 * volume (the automatic tolerance reduces the range of n - 1 across ranks). Those levels stop at
 * the piece's border, so vtkSchlierenImage, which gathers the whole volume, recomputes the levels
 * of the whole volume from `octree_tolerance` and `octree_max_level` instead of gathering them:
 * under MPI the array is a marker that says "use the octree at this tolerance".
 *
 * @sa vtkSchlierenImage vtkRefractiveIndex
 */
#ifndef vtkRefractionOctree_h
#define vtkRefractionOctree_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class SCHLIERENFILTERS_EXPORT vtkRefractionOctree : public vtkImageAlgorithm
{
public:
  static vtkRefractionOctree* New();
  vtkTypeMacro(vtkRefractionOctree, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The fraction of the range of n - 1 that the automatic tolerance (Tolerance 0) uses. */
  static constexpr double AutomaticToleranceFraction = 1e-4;

  ///@{
  /**
   * The largest spread of n - 1 (dimensionless, index units) that an octree block may hold.
   * 0 (the default) means automatic: AutomaticToleranceFraction times the range of n - 1.
   * Valid range [0, 1]; a value outside it is an error when the filter runs (never clamped).
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * The highest level: blocks of at most 2^MaxLevel cells along each axis, in [0, 10] (outside:
   * an error naming it). Default 7.
   */
  vtkSetMacro(MaxLevel, int);
  vtkGetMacro(MaxLevel, int);
  ///@}

protected:
  vtkRefractionOctree();
  ~vtkRefractionOctree() override;

public:
  /** Every request, with any exception turned into an error and a failed request. */
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  /** ParaView's executive that, under MPI, stops the filter on every rank at once where its
   * input failed on some (schlieren::NewAgreeingExecutive). */
  vtkExecutive* CreateDefaultExecutive() override;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double Tolerance = 0.0;
  int MaxLevel = 7;

private:
  vtkRefractionOctree(const vtkRefractionOctree&) = delete;
  void operator=(const vtkRefractionOctree&) = delete;
};

#endif
