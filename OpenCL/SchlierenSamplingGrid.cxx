// SPDX-License-Identifier: BSD-3-Clause
// RefractiveIndex's sampling grid, moving bounds and input request (SchlierenSamplingGrid.h).
#include "SchlierenSamplingGrid.h"

#include "SchlierenEngine.h"
#include "SchlierenIndexModels.h" // AutomaticDimensions
#include "SchlierenLimits.h"
#include "SchlierenParallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace schlieren
{
namespace
{
const char* const TypedBoundsSuffix = " (SamplingBounds: xmin xmax ymin ymax zmin zmax)";
}

bool SamplingSettings::Automatic() const
{
  return this->SamplingDimensions[0] <= 0 || this->SamplingDimensions[1] <= 0 ||
    this->SamplingDimensions[2] <= 0;
}

void PullIn(const double bounds[6], double box[6])
{
  const double s = 1.0 - 1e-6;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = bounds[2 * a], hi = bounds[2 * a + 1];
    const double c = 0.5 * (hi + lo);
    box[2 * a] = c + s * (lo - c);
    box[2 * a + 1] = c + s * (hi - c);
  }
}

void SamplingBox(const SamplingSettings& s, const double* inputBounds, double box[6])
{
  if (s.UseSamplingBounds)
  {
    std::copy(s.SamplingBounds, s.SamplingBounds + 6, box);
  }
  else
  {
    bool empty = inputBounds == nullptr;
    for (int a = 0; a < 3 && !empty; ++a)
      empty = !(inputBounds[2 * a] <= inputBounds[2 * a + 1]);
    if (empty)
      throw Error("The input has no points to resample onto an image grid.");
    PullIn(inputBounds, box);
  }
  try
  {
    int ignored[3];
    AutomaticDimensions(box, 2, ignored); // the box's checks
  }
  catch (const Error& e)
  {
    throw Error(std::string(e.what()) + (s.UseSamplingBounds ? TypedBoundsSuffix : ""));
  }
}

double SamplingBytesPerPoint(double arrayBytes)
{
  return 1.0 + 16.0 + arrayBytes;
}

SamplingGrid PlanSamplingGrid(
  const SamplingSettings& s, const double box[6], double arrayBytes, const AutomaticGrid& own)
{
  SamplingGrid g;
  const bool automatic = s.Automatic();
  try
  {
    if (automatic)
    {
      if (!(own && own(box, g.Dims)))
        AutomaticDimensions(box, s.AutomaticDimension, g.Dims);
    }
    else
    {
      std::copy(s.SamplingDimensions, s.SamplingDimensions + 3, g.Dims);
      int ignored[3];
      AutomaticDimensions(box, 2, ignored); // checks the box
    }
    std::ostringstream what;
    what << "Resampling onto " << g.Dims[0] << " x " << g.Dims[1] << " x " << g.Dims[2]
         << " points";
    CheckHostMemory(double(g.Dims[0]) * g.Dims[1] * g.Dims[2] * SamplingBytesPerPoint(arrayBytes),
      what.str(),
      automatic ? "Lower AutomaticDimension (points along the longest side)."
                : "Lower SamplingDimensions.");
  }
  catch (const Error& e)
  {
    throw Error(std::string(e.what()) + (s.UseSamplingBounds ? TypedBoundsSuffix : ""));
  }
  for (int a = 0; a < 3; ++a)
  {
    g.Whole[2 * a] = 0;
    g.Whole[2 * a + 1] = g.Dims[a] - 1;
    g.Origin[a] = box[2 * a];
    g.Spacing[a] = g.Dims[a] > 1 ? (box[2 * a + 1] - box[2 * a]) / (g.Dims[a] - 1) : 1.0;
  }
  return g;
}

bool FollowBounds(
  const SamplingGrid& grid, const double inputBounds[6], SamplingGrid& moved, std::string* note)
{
  if (!(inputBounds[0] <= inputBounds[1]))
    return false;
  double bounds[6];
  PullIn(inputBounds, bounds); // as SamplingBox
  bool changed = false;
  moved = grid;
  for (int a = 0; a < 3; ++a)
  {
    const int n = grid.Whole[2 * a + 1] - grid.Whole[2 * a];
    const double lo = grid.Origin[a] + grid.Whole[2 * a] * grid.Spacing[a];
    const double hi = grid.Origin[a] + grid.Whole[2 * a + 1] * grid.Spacing[a];
    const double size = std::max({ hi - lo, bounds[2 * a + 1] - bounds[2 * a], 1e-300 });
    changed = changed || std::fabs(bounds[2 * a] - lo) > 1e-9 * size ||
      (n > 0 && std::fabs(bounds[2 * a + 1] - hi) > 1e-9 * size);
    moved.Spacing[a] = n > 0 && bounds[2 * a + 1] > bounds[2 * a]
      ? (bounds[2 * a + 1] - bounds[2 * a]) / n
      : grid.Spacing[a];
    moved.Origin[a] = (n > 0 ? bounds[2 * a] : 0.5 * (bounds[2 * a] + bounds[2 * a + 1])) -
      grid.Whole[2 * a] * moved.Spacing[a];
  }
  if (!changed)
    return false;
  if (note)
  {
    std::ostringstream m;
    m << "RefractiveIndex: the input's bounds are not those the sampling grid was set over (a "
         "mesh that moves over time): the grid follows them, the same points over ["
      << bounds[0] << ", " << bounds[1] << "] x [" << bounds[2] << ", " << bounds[3] << "] x ["
      << bounds[4] << ", " << bounds[5] << "].";
    *note = m.str();
  }
  return true;
}

bool SplitExtent(
  int piece, int pieces, int ghosts, int splitMode, const int updateExtent[6], int extent[6])
{
  const int none[6] = { 0, -1, 0, -1, 0, -1 };
  std::copy(none, none + 6, extent);
  if (pieces < 1 || piece < 0 || piece >= pieces)
    return false;
  // by cells (the two halves share the points between them)
  long long e[6];
  for (int k = 0; k < 6; ++k)
    e[k] = updateExtent[k];
  // halve the chosen axis (the piece's share of the pieces) until one piece is left
  while (pieces > 1)
  {
    const long long size[3] = { e[1] - e[0], e[3] - e[2], e[5] - e[4] };
    int axis = -1;
    if (splitMode >= 0 && splitMode < 3 && size[splitMode] > 1)
      axis = splitMode;
    else if (size[2] >= size[1] && size[2] >= size[0] && size[2] / 2 >= 1)
      axis = 2;
    else if (size[1] >= size[0] && size[1] / 2 >= 1)
      axis = 1;
    else if (size[0] / 2 >= 1)
      axis = 0;
    if (axis < 0)
    {
      if (piece != 0)
        return true; // nothing left for this piece: empty
      break;
    }
    const int first = pieces / 2;
    const long long mid = size[axis] * first / pieces + e[2 * axis];
    if (piece < first)
    {
      e[2 * axis + 1] = mid;
      pieces = first;
    }
    else
    {
      e[2 * axis] = mid;
      pieces -= first;
      piece -= first;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (ghosts > 0)
    {
      e[2 * a] = std::max<long long>(e[2 * a] - ghosts, updateExtent[2 * a]);
      e[2 * a + 1] = std::min<long long>(e[2 * a + 1] + ghosts, updateExtent[2 * a + 1]);
    }
  }
  for (int k = 0; k < 6; ++k)
    extent[k] = static_cast<int>(e[k]);
  return true;
}

InputRequest RequestInput(bool resampled, bool symmetric, int rank, int ranks, int piece,
  int pieces, int ghosts, int splitMode, const int updateExtent[6], const int whole[6])
{
  InputRequest r;
  if (resampled || symmetric)
  {
    r.WholeExtent = true;
    r.Piece = symmetric || ranks <= 1 ? 0 : rank;
    r.Pieces = symmetric ? 1 : std::max(1, ranks);
    return r;
  }
  r.WholeExtent = false;
  std::copy(updateExtent, updateExtent + 6, r.Extent);
  if (pieces > 1)
    SplitExtent(piece, pieces, ghosts, splitMode, updateExtent, r.Extent);
  if (r.Extent[1] >= r.Extent[0] && r.Extent[3] >= r.Extent[2] && r.Extent[5] >= r.Extent[4])
  {
    // one more point on every side, so that central differences at the piece's borders use the
    // neighbours' values; clamped to the whole extent (where the engine goes one-sided)
    for (int a = 0; a < 3; ++a)
    {
      r.Extent[2 * a] = std::max(r.Extent[2 * a] - 1, whole[2 * a]);
      r.Extent[2 * a + 1] = std::min(r.Extent[2 * a + 1] + 1, whole[2 * a + 1]);
    }
  }
  return r;
}

std::string ExtentCoverProblem(const int extent[6], const int requested[6])
{
  for (int a = 0; a < 3; ++a)
  {
    if (requested[2 * a] < extent[2 * a] || requested[2 * a + 1] > extent[2 * a + 1])
    {
      std::ostringstream m;
      m << "The input's extent (" << extent[0] << " " << extent[1] << " " << extent[2] << " "
        << extent[3] << " " << extent[4] << " " << extent[5]
        << ") does not cover the requested extent (" << requested[0] << " " << requested[1] << " "
        << requested[2] << " " << requested[3] << " " << requested[4] << " " << requested[5]
        << "); the upstream filter did not honour the update request.";
      return m.str();
    }
  }
  return std::string();
}

std::string MissingArrayProblem(const std::vector<std::string>& names,
  const std::vector<std::string>& present, const std::string& model)
{
  for (const std::string& name : names)
  {
    if (std::find(present.begin(), present.end(), name) == present.end())
    {
      std::ostringstream m;
      m << model << " reads the array '" << name
        << "', which the input does not have. Arrays present: ";
      for (std::size_t i = 0; i < present.size(); ++i)
        m << (i ? ", " : "") << present[i];
      m << (present.empty() ? "none" : "") << ". Choose one of them.";
      return m.str();
    }
  }
  return std::string();
}

void AgreeOnRefusal(Parallel& parallel, const std::string& refused)
{
  if (parallel.Max(refused.empty() ? 0.0 : 1.0) > 0.5)
    throw Error(refused.empty() ? std::string("Another rank's piece of the input could not be "
                                              "resampled (its message says why).")
                                : refused);
}

void MergeProbedPieces(Parallel& parallel, const std::vector<unsigned char>& found,
  const std::vector<ProbedArray>& arrays, std::vector<unsigned char>& valid,
  std::vector<MergedArray>& merged)
{
  const std::size_t n = found.size();
  std::vector<double> total(n);
  for (std::size_t i = 0; i < n; ++i)
    total[i] = found[i] != 0 ? 1.0 : 0.0;
  parallel.Sum(total.data(), total.size());
  valid.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    valid[i] = total[i] > 0.0 ? 1 : 0;
  merged.clear();
  for (const ProbedArray& a : arrays) // the same list, in the same order, on every rank
  {
    const bool have = a.Have && a.Values.size() >= n;
    if (parallel.Max(have ? 1.0 : 0.0) < 0.5)
      continue; // no rank has it: reported as missing by the caller, the same on every rank
    std::vector<double> all(n, 0.0);
    if (have)
      for (std::size_t i = 0; i < n; ++i)
        if (found[i] != 0)
          all[i] = a.Values[i];
    parallel.Sum(all.data(), all.size());
    MergedArray m;
    m.Name = a.Name;
    m.Values.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      m.Values[i] = total[i] > 0.0 ? static_cast<float>(all[i] / total[i]) : 0.0f;
    merged.push_back(std::move(m));
  }
}

} // namespace schlieren
