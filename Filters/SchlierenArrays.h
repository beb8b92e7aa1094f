// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenArrays.h
 * @brief The names of the arrays and field data the filters pass to each other (DESIGN.md's
 * contract: users' scripts and ParaView states rely on them).
 */
#ifndef SchlierenArrays_h
#define SchlierenArrays_h

namespace schlieren
{
namespace arrays
{
/** Point data of RefractiveIndex and RefractiveScene, read by RefractionOctree and SchlierenImage. */
constexpr const char* NMinus1 = "n_minus_1";
constexpr const char* GradN = "grad_n";
/** 1 where a grid point lies in a solid body (RefractiveScene Body, RefractiveIndex BodyFromGrid). */
constexpr const char* Solid = "solid";
/** RefractionOctree's per-point level and its field data. */
constexpr const char* OctreeLevel = "octree_level";
constexpr const char* OctreeTolerance = "octree_tolerance";
constexpr const char* OctreeMaxLevel = "octree_max_level";
constexpr const char* OctreeSkippableFraction = "octree_skippable_fraction";
} // namespace arrays
} // namespace schlieren

#endif
