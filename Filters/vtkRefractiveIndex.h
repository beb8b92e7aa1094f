// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkRefractiveIndex
 * @brief   refractive index n - 1 and its gradient from a field of an image
 *
 * vtkRefractiveIndex turns one point array of a vtkImageData into the refractive index that the
 * schlieren tracer needs, by a Model:
 *
 * - PASSTHROUGH (0): the array already is n - 1 (dimensionless);
 * - GLADSTONE_DALE (1): the array is the density rho (kg/m^3) and n - 1 = K rho, with K the
 *   GladstoneDaleConstant (m^3/kg, default 2.256e-4: air at 632.8 nm).
 *
 * The array is chosen with SetInputArrayToProcess (index 0, point data; by default the active
 * scalars). Wavelength (nm, default 632.8) is kept for the wavelength-dependent models to come.
 *
 * The output is the input with two more point arrays: `n_minus_1` (float, the active scalars) and
 * `grad_n` (float, 3 components, per world unit: central differences in world units, one-sided at
 * the borders, spacing-aware; schlieren::ComputeGradient). The input's other arrays are kept.
 * NaN/Inf or n <= 0 anywhere is an error (schlieren::ValidateIndex).
 *
 * Under MPI the filter asks its input for one more point on every side of the requested piece, so
 * that the central differences at the piece borders are those of the whole volume.
 *
 * @warning Only vtkImageData inputs are accepted for now; resample other data sets onto an image
 * first (for example with ParaView's Resample To Image).
 *
 * @sa vtkRefractiveScene vtkSchlierenImage
 */
#ifndef vtkRefractiveIndex_h
#define vtkRefractiveIndex_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class SCHLIERENFILTERS_EXPORT vtkRefractiveIndex : public vtkImageAlgorithm
{
public:
  static vtkRefractiveIndex* New();
  vtkTypeMacro(vtkRefractiveIndex, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How the input array becomes n - 1. */
  enum ModelType
  {
    PASSTHROUGH = 0,   ///< the array is n - 1
    GLADSTONE_DALE = 1 ///< the array is the density; n - 1 = K rho
  };

  ///@{
  /**
   * The model (a ModelType). Default PASSTHROUGH.
   */
  vtkSetClampMacro(Model, int, PASSTHROUGH, GLADSTONE_DALE);
  vtkGetMacro(Model, int);
  void SetModelToPassthrough() { this->SetModel(PASSTHROUGH); }
  void SetModelToGladstoneDale() { this->SetModel(GLADSTONE_DALE); }
  ///@}

  ///@{
  /**
   * The Gladstone-Dale constant K, m^3/kg (1 cm^3/g = 1e-3 m^3/kg). Default 2.256e-4 (air at
   * 632.8 nm). Clamped to [0, 1]; it must be positive (0 is reported as an error).
   */
  vtkSetClampMacro(GladstoneDaleConstant, double, 0.0, 1.0);
  vtkGetMacro(GladstoneDaleConstant, double);
  ///@}

  ///@{
  /**
   * The light's vacuum wavelength, nm. Default 632.8 (HeNe). Clamped to [100, 20000]. Not used by
   * the current models; kept for the dispersive ones.
   */
  vtkSetClampMacro(Wavelength, double, 100.0, 20000.0);
  vtkGetMacro(Wavelength, double);
  ///@}

protected:
  vtkRefractiveIndex();
  ~vtkRefractiveIndex() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Model = PASSTHROUGH;
  double GladstoneDaleConstant = 2.256e-4;
  double Wavelength = 632.8;

private:
  vtkRefractiveIndex(const vtkRefractiveIndex&) = delete;
  void operator=(const vtkRefractiveIndex&) = delete;
};

#endif
