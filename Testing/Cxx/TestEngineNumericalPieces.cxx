// SPDX-License-Identifier: BSD-3-Clause
// NumericalSchlierenOfPieces on 1 to 4 in-process ranks: a volume split into slabs along z (uneven,
// neighbours sharing their boundary plane, one rank holding nothing on 4 ranks) gives rank 0 the
// image NumericalSchlieren makes of the whole volume, bit for bit (the gathered grid is the whole
// grid value for value, and the same code images it); the other ranks no image. A slab missing
// (points no rank holds) is an error on every rank, the same message (Parallel::Failure).
#include "SchlierenNumerical.h"
#include "SchlierenTesting.h"

#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

using namespace schlieren;

namespace
{
const int NX = 23, NY = 19, NZ = 17;

struct Whole
{
  std::vector<float> Values;
  std::vector<unsigned char> Solid, Excluded;
  ScalarGrid Grid;
};

/** A Gaussian density with a solid ball and a few excluded points, on [-1, 1] x ... */
Whole MakeWhole()
{
  Whole w;
  const std::size_t n = std::size_t(NX) * NY * NZ;
  w.Values.resize(n);
  w.Solid.assign(n, 0);
  w.Excluded.assign(n, 0);
  ScalarGrid& g = w.Grid;
  g.Dimensions[0] = NX;
  g.Dimensions[1] = NY;
  g.Dimensions[2] = NZ;
  for (int a = 0; a < 3; ++a)
  {
    g.Origin[a] = -1.0;
    g.Spacing[a] = 2.0 / (g.Dimensions[a] - 1);
  }
  for (int z = 0; z < NZ; ++z)
    for (int y = 0; y < NY; ++y)
      for (int x = 0; x < NX; ++x)
      {
        const std::size_t p = (std::size_t(z) * NY + y) * NX + x;
        const double X = g.Origin[0] + x * g.Spacing[0], Y = g.Origin[1] + y * g.Spacing[1],
                     Z = g.Origin[2] + z * g.Spacing[2];
        w.Values[p] = static_cast<float>(1.2 + 0.5 * std::exp(-(X * X + Y * Y + Z * Z) / 0.2));
        w.Solid[p] = (X - 0.5) * (X - 0.5) + Y * Y + Z * Z < 0.06 ? 1 : 0;
        w.Excluded[p] = (x == 0 && y < 3) ? 1 : 0;
      }
  g.Values = w.Values.data();
  g.Solid = w.Solid.data();
  g.Excluded = w.Excluded.data();
  return w;
}

/** Rank r's slab [z0, z1] of the whole grid (z1 < z0: none), as the engine takes a piece. */
ScalarGrid Slab(const Whole& w, int z0, int z1, int offset[3])
{
  ScalarGrid s = w.Grid;
  offset[0] = offset[1] = 0;
  offset[2] = z0;
  if (z1 < z0)
  {
    s.Dimensions[2] = 0;
    s.Values = nullptr;
    s.Solid = s.Excluded = nullptr;
    return s;
  }
  const std::size_t at = std::size_t(z0) * NX * NY;
  s.Dimensions[2] = z1 - z0 + 1;
  s.Origin[2] = w.Grid.Origin[2] + z0 * w.Grid.Spacing[2];
  s.Values = w.Values.data() + at;
  s.Solid = w.Solid.data() + at;
  s.Excluded = w.Excluded.data() + at;
  return s;
}

/** The slabs of n ranks: uneven, each sharing its first plane with the one before. */
std::vector<std::pair<int, int>> Slabs(int n, bool leaveOut)
{
  std::vector<std::pair<int, int>> s;
  if (n == 1)
    s = { { 0, NZ - 1 } };
  else if (n == 2)
    s = { { 0, 4 }, { 4, NZ - 1 } };
  else if (n == 3)
    s = { { 0, 9 }, { 9, 12 }, { 12, NZ - 1 } };
  else
    s = { { 0, 6 }, { 6, 11 }, { 1, 0 }, { 11, NZ - 1 } }; // rank 2 holds nothing
  if (leaveOut)
    s[n - 1].second = NZ - 3; // the last two planes held by no rank
  return s;
}
} // namespace

int main()
{
  const Whole w = MakeWhole();
  for (int mode = 0; mode < 2; ++mode)
  {
    NumericalSettings s;
    s.Mode = mode == 0 ? NumericalMode::Slice : NumericalMode::LineOfSight;
    s.Quantity = mode == 0 ? NumericalQuantity::Magnitude : NumericalQuantity::KnifeComponent;
    s.KnifeAngle = 30.0;
    s.SliceOffset = mode == 0 ? 0.1 : 0.0;
    s.ViewDirection[0] = mode == 0 ? 0.0 : -1.0;
    s.ViewDirection[2] = mode == 0 ? -1.0 : 0.0;
    s.ViewUp[1] = mode == 0 ? 1.0 : 0.0;
    s.ViewUp[2] = mode == 0 ? 0.0 : 1.0;
    s.Resolution[0] = 40;
    s.Resolution[1] = 36;
    const NumericalImage one = NumericalSchlieren(w.Grid, s);
    int blocked = 0;
    for (unsigned char b : one.Blocked)
      blocked += b;
    CHECK(blocked > 10 && one.Largest > 0, "the whole volume's image has a body and a gradient");
    for (int n = 1; n <= 4; ++n)
    {
      std::mutex m;
      int bad = 0, images = 0;
      bool equal = false;
      const auto slabs = Slabs(n, false);
      RunInProcessRanks(n, [&](Parallel& p) {
        int offset[3];
        const ScalarGrid piece = Slab(w, slabs[p.Rank()].first, slabs[p.Rank()].second, offset);
        ScalarGrid geometry = w.Grid;
        geometry.Values = nullptr;
        geometry.Solid = geometry.Excluded = nullptr;
        NumericalImage image;
        const bool has = NumericalSchlierenOfPieces(p, piece, offset, geometry, s, image);
        std::lock_guard<std::mutex> lock(m);
        if (has)
        {
          ++images;
          equal = p.Rank() == 0 && image.Intensity == one.Intensity && image.Gradient == one.Gradient &&
            image.Blocked == one.Blocked && image.Maximum == one.Maximum;
        }
        else if (!image.Intensity.empty())
          ++bad;
      });
      CHECK(images == 1 && bad == 0, std::string(mode ? "LineOfSight" : "Slice") + " on " +
          std::to_string(n) + " ranks: rank 0 alone holds an image");
      CHECK(equal, std::string(mode ? "LineOfSight" : "Slice") + " on " + std::to_string(n) +
          " ranks: the one-process image, bit for bit");
    }
  }

  // two planes no rank holds: the same error on every rank, no image, no hang
  for (int n = 2; n <= 3; ++n)
  {
    std::mutex m;
    std::vector<std::string> said(n);
    const auto slabs = Slabs(n, true);
    try
    {
      RunInProcessRanks(n, [&](Parallel& p) {
        int offset[3];
        const ScalarGrid piece = Slab(w, slabs[p.Rank()].first, slabs[p.Rank()].second, offset);
        ScalarGrid geometry = w.Grid;
        geometry.Values = nullptr;
        NumericalImage image;
        try
        {
          NumericalSchlierenOfPieces(p, piece, offset, geometry, NumericalSettings(), image);
        }
        catch (const Error& e)
        {
          std::lock_guard<std::mutex> lock(m);
          said[p.Rank()] = e.what();
        }
      });
    }
    catch (const Error&)
    {
    }
    const std::string expected = "NumericalSchlieren: the ranks' pieces leave " +
      std::to_string(2 * NX * NY) + " of the volume's " + std::to_string(NX * NY * NZ) +
      " points out (the input's pieces must cover its whole extent).";
    bool agreed = said[0] == expected;
    for (int r = 1; r < n; ++r)
      agreed = agreed && said[r] == "another rank (0) failed: " + expected;
    CHECK(agreed, "points no rank holds on " + std::to_string(n) + " ranks: every rank says so (" +
        said[0] + ")");
  }

  // Issue 48: NaN or Inf at a point of the flow is refused, as SchlierenImage refuses it (it gave
  // NaN pixels or a white image and a maximum of 0); at a solid or excluded point it is no part
  // of the image and is accepted.
  {
    Whole bad = MakeWhole();
    const std::size_t at = (std::size_t(13) * NY + 9) * NX + 11; // a flow point in rank 3's slab
    CHECK(!bad.Solid[at] && !bad.Excluded[at], "the NaN's point is a flow point");
    bad.Values[at] = std::numeric_limits<float>::quiet_NaN();
    bad.Values[at + 1] = std::numeric_limits<float>::infinity();
    bad.Grid.Values = bad.Values.data();
    schtest::ExpectError("NumericalSchlieren of a field with NaN and Inf",
      [&] { NumericalSchlieren(bad.Grid, NumericalSettings()); },
      { "2 of " + std::to_string(NX * NY * NZ) + " points of the flow are NaN or Inf",
        "i j k = 11 9 13" });
    Whole masked = MakeWhole();
    for (std::size_t p = 0; p < masked.Values.size(); ++p)
      if (masked.Solid[p] || masked.Excluded[p])
        masked.Values[p] = std::numeric_limits<float>::quiet_NaN();
    NumericalSettings s;
    s.Resolution[0] = 40;
    s.Resolution[1] = 36;
    const NumericalImage a = NumericalSchlieren(masked.Grid, s), b = NumericalSchlieren(w.Grid, s);
    CHECK(a.Intensity == b.Intensity && a.Maximum == b.Maximum && a.Maximum > 0,
      "NaN at solid and excluded points only: the image of the field without them, bit for bit");

    // on 4 ranks, the NaN in rank 3's piece: every rank stops with the one message, no hang
    const int n = 4;
    std::mutex m;
    std::vector<std::string> said(n);
    const auto slabs = Slabs(n, false);
    try
    {
      RunInProcessRanks(n, [&](Parallel& p) {
        int offset[3];
        const ScalarGrid piece = Slab(bad, slabs[p.Rank()].first, slabs[p.Rank()].second, offset);
        ScalarGrid geometry = bad.Grid;
        geometry.Values = nullptr;
        geometry.Solid = geometry.Excluded = nullptr;
        NumericalImage image;
        try
        {
          NumericalSchlierenOfPieces(p, piece, offset, geometry, NumericalSettings(), image);
        }
        catch (const Error& e)
        {
          std::lock_guard<std::mutex> lock(m);
          said[p.Rank()] = e.what();
        }
      });
    }
    catch (const Error&)
    {
    }
    bool agreed = said[0].find("points of the flow are NaN or Inf") != std::string::npos;
    for (int r = 1; r < n; ++r)
      agreed = agreed && said[r] == "another rank (0) failed: " + said[0];
    CHECK(agreed, "NaN in one piece of 4: every rank says so (" + said[0] + ")");
  }

  // AgreedFieldName (the filter's density array under MPI, issue 47 moved it into the engine): the
  // first non-empty piece's name on every rank; different names, every piece empty, or one rank's
  // error: the same Error on every rank (the others' prefixed "another rank (r) failed: ")
  {
    auto agree = [](const std::vector<std::string>& names, const std::vector<std::string>& errors) {
      const int n = static_cast<int>(names.size());
      std::mutex m;
      std::vector<std::string> said(n);
      try
      {
        RunInProcessRanks(n, [&](Parallel& p) {
          std::string out;
          try
          {
            out = "name " + AgreedFieldName(p, errors[p.Rank()], names[p.Rank()]);
          }
          catch (const Error& e)
          {
            out = e.what();
          }
          std::lock_guard<std::mutex> lock(m);
          said[p.Rank()] = out;
        });
      }
      catch (const Error&)
      {
      }
      return said;
    };
    const std::vector<std::string> none(3);
    CHECK(agree({ "", "rho", "rho" }, none) == std::vector<std::string>(3, "name rho"),
      "AgreedFieldName: an empty piece takes the others' name");
    const std::string differ = "NumericalSchlieren: the ranks' pieces carry different density "
                               "arrays ('density', 'rho'): name one in DensityArray.";
    CHECK(agree({ "density", "", "rho" }, none) == std::vector<std::string>(3, differ),
      "AgreedFieldName: two names, the one error on every rank");
    const std::vector<std::string> empty = agree({ "", "", "" }, none);
    CHECK(empty == std::vector<std::string>(3, empty[0]) &&
        empty[0].find("every rank's piece of the input is empty") != std::string::npos,
      "AgreedFieldName: every piece empty, said on every rank (" + empty[0] + ")");
    const std::vector<std::string> failed = agree({ "rho", "rho", "rho" }, { "", "no rho here", "" });
    CHECK(failed[1] == "no rho here" && failed[0] == "another rank (1) failed: no rho here" &&
        failed[2] == failed[0],
      "AgreedFieldName: rank 1's error, its own there and named as another's elsewhere");
    CHECK(agree({ "rho" }, { "" }) == std::vector<std::string>(1, "name rho"),
      "AgreedFieldName on one rank: its name");
  }
  return schtest::Finish();
}
