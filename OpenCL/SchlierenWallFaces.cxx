// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenWallFaces.h"

#include <cmath>
#include <sstream>

namespace schlieren
{
namespace walls
{

std::vector<unsigned char> ClassifyFaces(std::size_t faces, const std::int64_t* offsets,
  const std::int64_t* connectivity, std::size_t points, const double* normals,
  const double* velocity, double largestSpeed, int ignoreAxis, RimReport& report)
{
  std::vector<unsigned char> kind(faces, LeftOut);
  const double umax = largestSpeed;
  for (std::size_t f = 0; f < faces; ++f)
  {
    if (offsets[f + 1] - offsets[f] < 3)
    {
      continue;
    }
    const double* n = normals + 3 * f;
    if (ignoreAxis >= 0 && std::abs(n[ignoreAxis]) > std::cos(25.0 * 3.14159265358979 / 180.0))
    {
      continue;
    }
    const double* u = velocity + 3 * f;
    // fluid at rest says nothing (a quiescent far field as much as a wall): neither
    const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const bool moving = speed >= MovingFluid * umax;
    const bool wall = moving && std::abs(u[0] * n[0] + u[1] * n[1] + u[2] * n[2]) < WallFlux * speed;
    (wall ? report.WallFaces : moving ? report.FlowFaces : report.StillFaces) += 1;
    kind[f] = wall ? WallFace : moving ? FlowFace : StillFace;
  }
  // A few faces the flow crosses with only walls (or fluid at rest) beside them are a wall
  // where the flow turns onto it (a reattachment, a stagnation point): the velocity of the cell
  // beside the face is not along the face there. An inlet or an outlet is a patch of its own.
  std::vector<std::vector<std::size_t>> facesOf(points);
  for (std::size_t f = 0; f < faces; ++f)
  {
    if (kind[f] == LeftOut)
      continue;
    for (std::int64_t k = offsets[f]; k < offsets[f + 1]; ++k)
      facesOf[static_cast<std::size_t>(connectivity[k])].push_back(f);
  }
  std::vector<char> seen(faces, 0);
  std::vector<std::size_t> cluster;
  for (std::size_t f0 = 0; f0 < faces; ++f0)
  {
    if (kind[f0] != FlowFace || seen[f0])
      continue;
    cluster.assign(1, f0);
    seen[f0] = 1;
    bool besideWall = false;
    for (std::size_t c = 0; c < cluster.size(); ++c)
      for (std::int64_t k = offsets[cluster[c]]; k < offsets[cluster[c] + 1]; ++k)
        for (std::size_t g : facesOf[static_cast<std::size_t>(connectivity[k])])
        {
          if (kind[g] == FlowFace && !seen[g])
          {
            seen[g] = 1;
            cluster.push_back(g);
          }
          besideWall = besideWall || kind[g] == WallFace;
        }
    if (besideWall && cluster.size() <= FewFaces)
    {
      for (std::size_t g : cluster)
        kind[g] = WallFace;
      report.FlowFaces -= cluster.size();
      report.WallFaces += cluster.size();
      report.TurnedFaces += cluster.size();
    }
  }
  return kind;
}

std::string BesideWallsNote(const RimReport& report, std::size_t marked)
{
  std::ostringstream m;
  m << "RefractiveIndex: BodyFromGrid: of the mesh's "
    << report.WallFaces + report.FlowFaces + report.StillFaces << " boundary faces, "
    << report.WallFaces << " are walls (the flow runs along them: |" << report.Velocity
    << ".n| < " << 100 * WallFlux << " % of |" << report.Velocity << "| there"
    << (report.TurnedFaces ? ", or " + std::to_string(report.TurnedFaces) +
           " in groups of a few between walls, where the flow turns onto a wall"
                           : std::string())
    << "), " << report.FlowFaces << " are crossed by the flow, " << report.StillFaces
    << " have fluid at rest beside them; " << marked
    << " grid points of the voids beside them (not enclosed by the flow, on the domain's edge) "
       "are taken as a body.";
  return m.str();
}

} // namespace walls
} // namespace schlieren
