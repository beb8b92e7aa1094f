// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSchlierenPhotograph
 * @brief   a laboratory photograph beside a traced image: registered onto the film, calibrated,
 *          overlaid and compared line by line
 *
 * Input 0: the output of vtkSchlierenImage (a 2D image with the point array `intensity`, square
 * pixels in world units of the film plane). The photograph: input 1 (optional, any vtkImageData:
 * its scalars) or else FileName (PNG, JPEG, TIFF, BMP, PNM: whatever vtkImageReader2Factory
 * reads; 8 or 16 bit; colour is made grey by its Rec. 709 luminance, alpha ignored).
 * schlieren::RegisterPhotograph does the work (OpenCL/SchlierenPhotograph.h, docs/CFD.md "A
 * photograph beside the image"): a start from the bench (PhotoPixelSize, world units a photograph
 * pixel) or 2-4 typed PointPairs, refined by a normalised correlation of the two images' gradient
 * maps over a similarity transform (Refine); the photograph's grey fitted to the film's; the
 * strong-gradient lines of both and their distances in world units.
 *
 * Output 0, on the film's grid: the point arrays `intensity` (the film), `photograph` (the
 * registered photograph's grey, 0 where it does not cover the film), `photograph_calibrated` (in
 * the film's grey), `difference` (calibrated - film), `checkerboard` (squares of CheckerSize
 * pixels), `blend` (film + BlendWeight * difference) and `line_distance` (world units at the film's
 * line pixels, NaN elsewhere), Overlay's array the active scalars; the field data
 * `photograph_report` (the engine's JSON: transform, uncertainty, score, threshold, grey fit,
 * lines), `photograph_score`, `_threshold`, `_scale`, `_rotation` (deg), `_shift` (2, photograph
 * pixels), `_photo_pixel_size`, `_edge_uncertainty` (film pixels), `_gamma`, `_gamma_error`,
 * `_background`, `_vignetting`, and `photograph_grey_reason`, `warnings` where there is one.
 * Output 1: the lines as polylines on the film plane, one cell a line, cell arrays `image` (0 the
 * film's, 1 the photograph's), `line_distance` (world units; NaN: not matched), `line_offset` (2),
 * `line_matched` (fraction), `line_match` (the other image's line, -1: none).
 *
 * Changing Overlay or BlendWeight alone does not register again (the last registration is kept
 * while the film, the photograph file or input and the engine's settings stay the same).
 *
 * A photograph that does not match (another flow, noise, a blank image) fails the request with the
 * engine's reason; the outputs stay empty. The Python package's SchlierenPhotograph gives the same
 * arrays bit for bit (Testing/Python/test_photograph.py).
 *
 * @sa vtkSchlierenImage
 */
#ifndef vtkSchlierenPhotograph_h
#define vtkSchlierenPhotograph_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string>

class SCHLIERENFILTERS_EXPORT vtkSchlierenPhotograph : public vtkImageAlgorithm
{
public:
  static vtkSchlierenPhotograph* New();
  vtkTypeMacro(vtkSchlierenPhotograph, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum RefineModes
  {
    SIMILARITY = 0,
    RIGID = 1,
    SHIFT = 2,
    NONE = 3
  };
  enum Overlays
  {
    BLEND = 0,
    CHECKERBOARD = 1,
    DIFFERENCE = 2,
    PHOTOGRAPH = 3,
    IMAGE = 4
  };

  ///@{
  /** The photograph's file (used where input 1 is not connected). */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}
  ///@{
  /** World units a photograph pixel (camera pixel / magnification); 0 (default): unknown. */
  vtkSetMacro(PhotoPixelSize, double);
  vtkGetMacro(PhotoPixelSize, double);
  ///@}
  ///@{
  /** 2 to 4 point pairs, numbers separated by spaces: photograph pixel u v, world x y; "": none. */
  vtkSetStdStringFromCharMacro(PointPairs);
  vtkGetCharFromStdStringMacro(PointPairs);
  ///@}
  ///@{
  /** What the correlation refines: SIMILARITY (default), RIGID, SHIFT, NONE. */
  vtkSetMacro(Refine, int);
  vtkGetMacro(Refine, int);
  ///@}
  ///@{
  /** Factors about the start scale searched where the scale is not known (0.6, 1.6). */
  vtkSetVector2Macro(ScaleRange, double);
  vtkGetVector2Macro(ScaleRange, double);
  ///@}
  ///@{
  /** Rotation searched, +- degrees (12); shift searched, a fraction of the film's larger side (0.3). */
  vtkSetMacro(MaxRotation, double);
  vtkGetMacro(MaxRotation, double);
  vtkSetMacro(MaxShift, double);
  vtkGetMacro(MaxShift, double);
  ///@}
  ///@{
  /** A line: a ridge of the gradient above this fraction of the strongest (0.25); lines shorter
   * than MinLineLength film pixels (8) dropped; lines farther apart than MaxLineDistance (world;
   * 0: a tenth of the film) not matched. */
  vtkSetMacro(LineThreshold, double);
  vtkGetMacro(LineThreshold, double);
  vtkSetMacro(MinLineLength, int);
  vtkGetMacro(MinLineLength, int);
  vtkSetMacro(MaxLineDistance, double);
  vtkGetMacro(MaxLineDistance, double);
  ///@}
  ///@{
  /** The active scalars of output 0: BLEND (default), CHECKERBOARD, DIFFERENCE, PHOTOGRAPH (the
   * calibrated photograph), IMAGE (the film). */
  vtkSetMacro(Overlay, int);
  vtkGetMacro(Overlay, int);
  ///@}
  ///@{
  /** The photograph's share of the blend, [0, 1] (0.5); the checkerboard's squares, pixels (16). */
  vtkSetMacro(BlendWeight, double);
  vtkGetMacro(BlendWeight, double);
  vtkSetMacro(CheckerSize, int);
  vtkGetMacro(CheckerSize, int);
  ///@}

  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  vtkSchlierenPhotograph();
  ~vtkSchlierenPhotograph() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  double PhotoPixelSize = 0.0;
  std::string PointPairs;
  int Refine = SIMILARITY;
  double ScaleRange[2] = { 0.6, 1.6 };
  double MaxRotation = 12.0;
  double MaxShift = 0.3;
  double LineThreshold = 0.25;
  int MinLineLength = 8;
  double MaxLineDistance = 0.0;
  int Overlay = BLEND;
  double BlendWeight = 0.5;
  int CheckerSize = 16;

private:
  /** The last registration, kept while the film, the photograph and the engine's settings stay
   * the same: Overlay and Blend Weight change the view without registering again. */
  class vtkInternals;
  vtkInternals* Internals;

  vtkSchlierenPhotograph(const vtkSchlierenPhotograph&) = delete;
  void operator=(const vtkSchlierenPhotograph&) = delete;
};

#endif
