// SPDX-License-Identifier: BSD-3-Clause
// The kernels read the packed field in bricks of 4^3 points (SchlierenPhysics.h, sch_axis_offset;
// BrickedField), so that oblique rays read the lines their neighbours read (issue 50). Only the
// addresses change: every image and record must be the one the linear layout gives, bit for bit,
// on both backends, both reconstructions, along the axis and obliquely, on a grid that is no
// multiple of the brick (the padding), and with the field split in slabs along z. The prefetch of
// each step's next lines (sch_prefetch_at, asked for here on this small grid) changes nothing
// either: off, the bits are the same.
#include "SchlierenEngineInternal.h" // the packing in bricks, PackInBricks
#include "SchlierenLimits.h"
#include "SchlierenParallel.h"
#include "SchlierenSession.h"
#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace schlieren;

namespace
{
bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
} // namespace

int main()
{
  // A front end may let go of the kept volume after the exit handlers have run (ParaView destroys
  // its session's filters, and their TraceSession, at pvpython's exit): the kept bricks must still
  // be there to let go of. Registered before anything is kept, this handler runs after the
  // destructors of the statics made later: the bricks were kept in one, and releasing them here
  // freed them twice (glibc: "corrupted double-linked list", an abort at exit; the stamped trace
  // at the end keeps them).
  std::atexit([] { ReleaseKeptVolume(); });
  const bool haveCL = schtest::HaveOpenCL();
  // the variable: 0 or 1, anything else an error that names it; off by default
  CHECK(RuntimeOptions().Bricks == -1, "unset by default: bricks where they pay");
  setenv("SCHLIEREN_FIELD_BRICKS", "1", 1);
  CHECK(RuntimeOptions::FromEnvironment().Bricks == 1, "SCHLIEREN_FIELD_BRICKS=1");
  setenv("SCHLIEREN_FIELD_BRICKS", "yes", 1);
  schtest::ExpectError("SCHLIEREN_FIELD_BRICKS=yes", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_FIELD_BRICKS", "0 or 1" });
  unsetenv("SCHLIEREN_FIELD_BRICKS");
  // the prefetch (sch_prefetch_at): on unless SCHLIEREN_PREFETCH=0
  CHECK(RuntimeOptions().Prefetch == -1, "unset by default: the prefetch where it pays");
  setenv("SCHLIEREN_PREFETCH", "0", 1);
  CHECK(RuntimeOptions::FromEnvironment().Prefetch == 0, "SCHLIEREN_PREFETCH=0");
  setenv("SCHLIEREN_PREFETCH", "on", 1);
  schtest::ExpectError("SCHLIEREN_PREFETCH=on", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_PREFETCH", "0 or 1" });
  unsetenv("SCHLIEREN_PREFETCH");
  // where it pays (docs/PERFORMANCE.md, "The prefetch"): obliquely past 200^3 points, along an
  // axis past 300^3 in bricks, never within the caches' reach
  {
    auto pays = [](int n, double dx, double dy, double dz, bool linear = false) {
      sch_params P;
      std::memset(&P, 0, sizeof(P));
      P.nx = P.ny = P.nz = n;
      P.fieldShift = linear ? 31 : 2;
      const double l = std::sqrt(dx * dx + dy * dy + dz * dz);
      P.dx = static_cast<float>(dx / l);
      P.dy = static_cast<float>(dy / l);
      P.dz = static_cast<float>(dz / l);
      return PrefetchPays(P);
    };
    CHECK(pays(512, 0, 0, -1) && pays(384, 0.05, 0.03, -1) && pays(512, 1, 0.7, -0.4), "512^3, 384^3 in bricks: on");
    CHECK(!pays(512, 0, 0, -1, true) && pays(512, 1, 0.7, -0.4, true),
      "512^3 in the linear layout: off along an axis, on obliquely");
    CHECK(pays(256, 1, 0.7, -0.4, true) && !pays(256, 0, 0, -1, true) && !pays(256, 0.05, 0.03, -1, true),
      "256^3: on obliquely, off along an axis");
    CHECK(!pays(128, 1, 0.7, -0.4) && !pays(64, 1, 1, 1), "128^3 and 64^3: off");
    const schtest::ScopedOptions on([](RuntimeOptions& opt) { opt.Prefetch = 1; });
    CHECK(pays(64, 0, 0, 1), "SCHLIEREN_PREFETCH=1: on everywhere");
  }
  // a Gaussian sphere on 37 x 34 x 29 points: 3, 2 and 1 padded points along x, y, z
  SceneParameters p;
  p.Amplitude = 2e-4;
  p.Width = 0.25;
  Volume v;
  const int dims[3] = { 37, 34, 29 };
  for (int a = 0; a < 3; ++a)
  {
    v.Dimensions[a] = dims[a];
    v.Origin[a] = -1;
    v.Spacing[a] = 2.0 / (dims[a] - 1);
  }
  std::vector<float> n1(v.NumberOfPoints());
  FillScene(Scene::GaussianSphere, p, v.Dimensions, v.Origin, v.Spacing, n1.data(), nullptr);
  AlignedFloats packed(4 * n1.size());
  std::vector<unsigned char> smooth(n1.size()), levels(n1.size());
  PackFieldHighOrder(v.Dimensions, v.Spacing, n1.data(), packed.data(), smooth.data());
  ComputeOctreeLevels(v.Dimensions, n1.data(), 1e-7, levels.data());
  v.Field = packed.data();
  v.Smooth = smooth.data();
  v.Levels = levels.data();

  const double views[3][3] = { { 0, 0, -1 }, { 1, 0.7, -0.4 }, { -0.3, -1, 0.2 } };
  std::vector<float> ab;
  for (int k = 0; k < 64; ++k)
  {
    ab.push_back(static_cast<float>(-0.8 + 1.6 * ((k * 37) % 64) / 63.0));
    ab.push_back(static_cast<float>(-0.8 + 1.6 * k / 63.0));
  }
  int compared = 0;
  for (Backend b : { Backend::CPU, Backend::OpenCL })
  {
    if (b == Backend::OpenCL && !haveCL)
      continue;
    // OpenCL once more with buffers of at most 300 kB: the field in 3 slabs (linear) and 4
    // (bricks: layers of 4 planes, 92 kB each)
    for (std::uint64_t maxAlloc : { std::uint64_t(0), std::uint64_t(300000) })
    {
      if (b == Backend::CPU && maxAlloc)
        continue;
      // (OpenCL: one program a setting, built afresh in CI: RK4, two views; Cubic, which is
      // trilinear at the border cells, in one buffer; Trilinear in slabs, where Cubic is
      // trilinear at the slabs' first and last cells too, and the slabs of the two layouts are
      // not the same: 13 planes linear, 8 in bricks)
      for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
        for (int view = 0; view < 3; ++view)
          for (Integrator m : { Integrator::RK4, Integrator::Euler })
          {
            if (b == Backend::OpenCL &&
              (m == Integrator::Euler || view == 2 || (rc == Reconstruction::Cubic) == (maxAlloc != 0)))
              continue;
            TraceSettings s;
            s.Device = b;
            s.Recon = rc;
            s.Method = m;
            s.StepSize = m == Integrator::RK4 ? 0.7 : 1.3;
            s.UseOctree = m == Integrator::Euler; // skips through the octree's blocks
            s.Resolution[0] = s.Resolution[1] = 40;
            s.Passes = 2;
            s.CutoffScale = 1000;
            for (int a = 0; a < 3; ++a)
              s.ViewDirection[a] = views[view][a];
            // [2]: the bricks again with the prefetch off (SCHLIEREN_PREFETCH=0), which must
            // change nothing either
            TraceResult r[3];
            std::vector<RayRecord> rec[3];
            for (int layout = 0; layout < 3; ++layout)
            {
              const schtest::ScopedOptions o([&](RuntimeOptions& opt) {
                opt.Bricks = layout >= 1 ? 1 : 0;
                opt.Prefetch = layout != 2 ? 1 : 0;
                opt.MaxAlloc = maxAlloc;
              });
              r[layout] = Trace(v, s);
              rec[layout] = TraceRays(v, s, ab);
            }
            const std::string what = std::string(b == Backend::CPU ? "CPU" : "OpenCL") +
              (maxAlloc ? " in slabs" : "") + ", " + ReconstructionName(rc) + ", " + IntegratorName(m) +
              ", view " + std::to_string(view);
            CHECK(SameBits(r[0].Intensity, r[1].Intensity), what + ": the image differs with the field in bricks");
            CHECK(SameBits(r[0].Deflection, r[1].Deflection), what + ": the deflections differ with the field in bricks");
            CHECK(r[0].Samples == r[1].Samples && r[0].Samples > 0, what + ": the samples differ");
            CHECK(rec[0].size() == ab.size() / 2 &&
                std::memcmp(rec[0].data(), rec[1].data(), rec[0].size() * sizeof(RayRecord)) == 0,
              what + ": the ray records differ with the field in bricks");
            CHECK(SameBits(r[1].Intensity, r[2].Intensity) && SameBits(r[1].Deflection, r[2].Deflection) &&
                r[1].Samples == r[2].Samples && rec[2].size() == rec[1].size() &&
                std::memcmp(rec[1].data(), rec[2].data(), rec[1].size() * sizeof(RayRecord)) == 0,
              what + ": the image or the records differ without the prefetch");
            if (maxAlloc)
            {
              CHECK(r[0].DeviceName.find("split in 3 buffers") != std::string::npos,
                what + ": the linear field in 3 slabs: " + r[0].DeviceName);
              CHECK(r[1].DeviceName.find("split in 4 buffers") != std::string::npos,
                what + ": the bricks in 4 slabs: " + r[1].DeviceName);
            }
            ++compared;
          }
    }
  }
  // The packing writes the bricks in place (Volume::FieldInBricks, what a TraceSession packs):
  // the floats of the copy made from the linear field, the padding included, for both packings
  {
    Volume linear = v;
    AlignedFloats inPlace(FieldLayout(v.Dimensions, true).Floats);
    std::vector<unsigned char> smoothInPlace(n1.size());
    // (NaN first: every float must be written, the padding too)
    std::fill(inPlace.begin(), inPlace.end(), std::nanf(""));
    float lo, hi;
    CHECK(ScanIndex(n1.data(), n1.size(), lo, hi).empty(), "the field is usable");
    PackFieldHighOrderOf(v.Dimensions, v.Spacing, n1.data(), inPlace.data(), smoothInPlace.data(),
      DefaultSmoothnessThreshold, lo, hi, 7, true);
    const auto copy = BrickedField(linear);
    CHECK(copy->size() == inPlace.size() &&
        std::memcmp(copy->data(), inPlace.data(), inPlace.size() * sizeof(float)) == 0,
      "PackFieldHighOrderOf in bricks: the copy of the linear field in bricks");
    CHECK(smoothInPlace == smooth, "the smoothness bytes stay linear");
    AlignedFloats second(4 * n1.size()), secondInPlace(inPlace.size());
    PackFieldOf(v.Dimensions, v.Spacing, n1.data(), second.data());
    std::fill(secondInPlace.begin(), secondInPlace.end(), std::nanf(""));
    PackFieldOf(v.Dimensions, v.Spacing, n1.data(), secondInPlace.data(), true);
    linear.Field = second.data();
    const auto copy2 = BrickedField(linear);
    CHECK(copy2->size() == secondInPlace.size() &&
        std::memcmp(copy2->data(), secondInPlace.data(), secondInPlace.size() * sizeof(float)) == 0,
      "PackFieldOf in bricks: the copy of the linear field in bricks");
    CHECK(FieldLayout(v.Dimensions, false).Floats == 4 * n1.size() &&
        inPlace.size() == std::size_t(40) * 36 * 32 * 4,
      "linear: 4 floats a point; bricks: the grid rounded up to whole bricks, 40 x 36 x 32");
  }
  // The default (SCHLIEREN_FIELD_BRICKS unset): a session packs in bricks where they pay, large
  // grids (docs/PERFORMANCE.md); 0 and 1 force either; a grid whose layer of bricks is past the
  // kernels' int strides stays linear.
  {
    const int small[3] = { 64, 64, 64 }, large[3] = { 512, 512, 512 }, wide[3] = { 40000, 40000, 8 };
    const schtest::ScopedOptions o([](RuntimeOptions& opt) { opt.Bricks = -1; });
    CHECK(!PackInBricks(small), "64^3 packs linear by default");
    CHECK(PackInBricks(large), "512^3 packs in bricks by default (every backend and reconstruction)");
    const int thin[3] = { 2000, 2000, 9 }, flat[3] = { 1000, 1000, 30 };
    CHECK(!PackInBricks(thin) && PackInBricks(flat),
      "not where the padding adds more than a tenth (9 planes in 12; 30 in 32 is in bricks)");
    CHECK(!BricksFit(wide) && !PackInBricks(wide), "a layer of bricks past 2^31 floats: linear");
    const schtest::ScopedOptions one([](RuntimeOptions& opt) { opt.Bricks = 1; });
    CHECK(PackInBricks(small) && PackInBricks(dims), "SCHLIEREN_FIELD_BRICKS=1: bricks everywhere");
    CHECK(!PackInBricks(wide), "SCHLIEREN_FIELD_BRICKS=1: never where they do not fit");
    const schtest::ScopedOptions zero([](RuntimeOptions& opt) { opt.Bricks = 0; });
    CHECK(!PackInBricks(large), "SCHLIEREN_FIELD_BRICKS=0: linear everywhere");
  }
  // A TraceSession packs in bricks in place: the same images, bit for bit, on both backends, both
  // reconstructions, an oblique view framed to the silhouette (which reads the packed gradient)
  {
    VolumePiece piece;
    for (int a = 0; a < 3; ++a)
    {
      piece.WholeExtent[2 * a] = piece.Extent[2 * a] = 0;
      piece.WholeExtent[2 * a + 1] = piece.Extent[2 * a + 1] = dims[a] - 1;
      piece.Origin[a] = v.Origin[a];
      piece.Spacing[a] = v.Spacing[a];
    }
    piece.Version = 1;
    piece.Load = [&n1](PieceValues& values) {
      values.NMinus1 = n1;
      return std::string();
    };
    for (Backend b : { Backend::CPU, Backend::OpenCL })
      for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
      {
        if (b == Backend::OpenCL && !haveCL)
          continue;
        TraceSettings s;
        s.Device = b;
        s.Recon = rc;
        s.Method = Integrator::RK4;
        s.StepSize = 0.7;
        s.Resolution[0] = s.Resolution[1] = 40;
        s.Passes = 2;
        s.CutoffScale = 1000;
        s.Frame = Framing::Silhouette;
        for (int a = 0; a < 3; ++a)
          s.ViewDirection[a] = views[1][a];
        SessionImage out[2];
        for (int layout = 0; layout < 2; ++layout)
        {
          const schtest::ScopedOptions o([&](RuntimeOptions& opt) { opt.Bricks = layout; });
          TraceSession session;
          session.Update(SerialParallel(), piece, s, out[layout]);
          CHECK(session.KeptVolume().FieldInBricks == (layout == 1), "the session's field layout");
        }
        const std::string what = std::string("a session, ") + (b == Backend::CPU ? "CPU, " : "OpenCL, ") +
          ReconstructionName(rc);
        CHECK(out[0].HasImage && out[1].HasImage && out[0].Result.Samples > 0 &&
            out[0].Result.Samples == out[1].Result.Samples,
          what + ": the samples differ");
        CHECK(std::equal(out[0].Traced.FilmExtent, out[0].Traced.FilmExtent + 4, out[1].Traced.FilmExtent),
          what + ": the silhouette's frame differs");
        CHECK(SameBits(out[0].Result.Intensity, out[1].Result.Intensity),
          what + ": the image differs with the field packed in bricks");
        ++compared;
      }
  }
  // a stamped volume: its bricks are kept for the next trace (and let go of at exit, above)
  {
    v.Stamp = NewVolumeStamp();
    const schtest::ScopedOptions o([](RuntimeOptions& opt) { opt.Bricks = 1; });
    TraceSettings s;
    s.Device = Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 16;
    s.Passes = 1;
    CHECK(Trace(v, s).Samples > 0, "a stamped volume traced in bricks");
  }
  std::printf("%d settings compared, linear against bricks\n", compared);
  CHECK(compared == (haveCL ? 20 : 14), "every setting compared");
  return schtest::Finish();
}
