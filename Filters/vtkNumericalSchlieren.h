// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkNumericalSchlieren
 * @brief   "numerical schlieren": Quirk's grey scale of the density gradient, beside the traced image
 *
 * The image CFD papers print: I = exp(-K S), S = (q - C0 qmax) / ((C1 - C0) qmax) clamped to
 * [0, 1], q = |grad rho| (Gradient Magnitude) or |grad rho . a| (KnifeComponent, a the knife
 * normal at KnifeAngle in the film plane), on the plane normal to ViewDirection at SliceOffset
 * from the volume's centre (Mode Slice) or averaged along the view through the volume (Mode
 * LineOfSight). No light is traced (schlieren::NumericalSchlieren does the work); the film is the
 * one vtkSchlierenImage makes for the same ViewDirection, ViewUp and Resolution, so the two images
 * line up pixel for pixel.
 *
 * Input: an image with the point array DensityArray; left empty, the first of `density`, `rho`,
 * `Density` that the image has, else `n_minus_1` (proportional to the density under
 * Gladstone-Dale, n - 1 = K rho; under a mixture or Ciddor only approximately). Points where
 * `solid` is non-zero are a body (black, `blocked`); points where `vtkValidPointMask` is 0 (outside
 * the CFD mesh) take no part in the differences.
 *
 * Output: a 2D image with the point arrays `intensity` (float, 0-1), `numerical_gradient` (q, or
 * the signed knife component, field units per world unit), `blocked` (unsigned char), and the
 * field data `numerical_field` (the array used), `numerical_mode`, `numerical_gradient_kind`,
 * `gradient_maximum` (the qmax used) and `gradient_largest` (the largest q over the image).
 *
 * Under MPI each rank reads its piece of the volume; the pieces are gathered on rank 0, which makes
 * the image as one process does (schlieren::NumericalSchlierenOfPieces) and holds it.
 */
#ifndef vtkNumericalSchlieren_h
#define vtkNumericalSchlieren_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string>

class SCHLIERENFILTERS_EXPORT vtkNumericalSchlieren : public vtkImageAlgorithm
{
public:
  static vtkNumericalSchlieren* New();
  vtkTypeMacro(vtkNumericalSchlieren, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    SLICE = 0,
    LINE_OF_SIGHT = 1
  };
  enum Gradients
  {
    MAGNITUDE = 0,
    KNIFE_COMPONENT = 1
  };

  /** The beam's direction and the film's up, as vtkSchlierenImage's. */
  vtkSetVector3Macro(ViewDirection, double);
  vtkGetVector3Macro(ViewDirection, double);
  vtkSetVector3Macro(ViewUp, double);
  vtkGetVector3Macro(ViewUp, double);
  /** Film pixels, 1 to 16384 each. */
  vtkSetVector2Macro(Resolution, int);
  vtkGetVector2Macro(Resolution, int);
  /** SLICE (default) or LINE_OF_SIGHT. */
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  /** MAGNITUDE (default) or KNIFE_COMPONENT. */
  vtkSetMacro(Gradient, int);
  vtkGetMacro(Gradient, int);
  /** Degrees in the film plane, [-180, 180]; 0: knife normal along the film's x. */
  vtkSetMacro(KnifeAngle, double);
  vtkGetMacro(KnifeAngle, double);
  /** The slice's world offset along ViewDirection from the volume's centre. */
  vtkSetMacro(SliceOffset, double);
  vtkGetMacro(SliceOffset, double);
  /** LineOfSight: voxels between samples, [0.05, 8]. */
  vtkSetMacro(StepSize, double);
  vtkGetMacro(StepSize, double);
  /** Quirk's scale: C0 in [-1, 0], C1 in [0.001, 1] (fractions of qmax), K in [0.001, 100]. */
  vtkSetMacro(C0, double);
  vtkGetMacro(C0, double);
  vtkSetMacro(C1, double);
  vtkGetMacro(C1, double);
  vtkSetMacro(K, double);
  vtkGetMacro(K, double);
  /** qmax; 0 (default): the largest q over the image (a fixed value keeps frames comparable). */
  vtkSetMacro(GradientMaximum, double);
  vtkGetMacro(GradientMaximum, double);
  /** The density's point array; empty (default): automatic (see the class comment). */
  vtkSetStdStringFromCharMacro(DensityArray);
  vtkGetCharFromStdStringMacro(DensityArray);

  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  /** ParaView's executive that, under MPI, stops the filter on every rank at once where its
   * input failed on some (schlieren::NewAgreeingExecutive). */
  vtkExecutive* CreateDefaultExecutive() override;

  vtkNumericalSchlieren();
  ~vtkNumericalSchlieren() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double ViewDirection[3] = { 0, 0, -1 };
  double ViewUp[3] = { 0, 1, 0 };
  int Resolution[2] = { 512, 512 };
  int Mode = SLICE;
  int Gradient = MAGNITUDE;
  double KnifeAngle = 0.0;
  double SliceOffset = 0.0;
  double StepSize = 0.5;
  double C0 = -0.001;
  double C1 = 0.05;
  double K = 5.0;
  double GradientMaximum = 0.0;
  std::string DensityArray;

private:
  vtkNumericalSchlieren(const vtkNumericalSchlieren&) = delete;
  void operator=(const vtkNumericalSchlieren&) = delete;
};

#endif
