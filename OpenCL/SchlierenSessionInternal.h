// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenSessionInternal.h
 * @brief Internal (not installed): what the two update paths of TraceSession share
 * (SchlierenSession.cxx: every rank with the whole volume; SchlierenSessionPieces.cxx: in pieces).
 */
#ifndef SchlierenSessionInternal_h
#define SchlierenSessionInternal_h

#include "SchlierenSession.h"

#include <cstddef>
#include <string>

namespace schlieren
{

/** The points of an inclusive extent (0 where it is empty). */
std::size_t ExtentPoints(const int ext[6]);

/** Throws on every rank where any rank failed: on a rank that failed its own message, on the
 * others the lowest failing rank's, as Parallel::Failure words it. Collective. */
void AgreeOrThrow(Parallel& parallel, const std::string& mine);

/**
 * This rank's piece values (piece.Load), or why they cannot be had: the piece's own problem,
 * Passes below 1, a failed or short load, too little memory; on one rank an empty input is one
 * too. Not collective: agree on the answer with AgreeOrThrow.
 */
std::string LoadPiece(
  const VolumePiece& piece, const TraceSettings& settings, int ranks, PieceValues& values);

/** LoadPiece on every rank, agreed (AgreeOrThrow), then that every rank's piece is of the same
 * whole grid (extent, origin, spacing): the collectives after it size their messages by that
 * grid, so a rank with another one would leave them mismatched (MPI aborts the job). Throws on
 * every rank where a rank disagrees. Collective. */
void LoadPieceAgreed(Parallel& parallel, const VolumePiece& piece, const TraceSettings& settings,
  PieceValues& values);

} // namespace schlieren

#endif
