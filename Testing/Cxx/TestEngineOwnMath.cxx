// SPDX-License-Identifier: BSD-3-Clause
// The engine's own elementary functions (SchlierenPhysics.h: sch_acos, sch_atan2, sch_erfc,
// sch_exp, sch_cos in float; sch_atan_d, sch_acos_d, sch_hypot_d, sch_exp_d, sch_tanh_d in double,
// host only)
// give the same bits everywhere: a hash of their results over 200000 fixed inputs each equals the
// one recorded on Debian 12 (GCC 12), which Zig's build for glibc 2.28 and mingw-w64's under wine
// gave too (docs/BUILDING.md "The same bits on every glibc"). And they are accurate: within the
// stated ulps of the C library's double functions. A different hash means the images are no longer
// the same bits as on the other platforms: a compiler that fuses a * b + c (FMA contraction, e.g.
// -march=haswell with GCC's default -ffp-contract=fast) or a changed polynomial.
#include "SchlierenPhysics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace
{
int failures = 0;
std::uint64_t state = 88172645463325252ull;
double Uniform(double lo, double hi)
{
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return lo + (hi - lo) * double(state >> 11) * (1.0 / 9007199254740992.0);
}
struct Hash
{
  std::uint64_t h = 1469598103934665603ull;
  template <typename T>
  void Add(T v)
  {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (unsigned char c : b)
      h = (h ^ c) * 1099511628211ull;
  }
};
double Ulps(double got, double want, bool single)
{
  const double a = std::fabs(want);
  const double ulp = single ? double(std::nextafter(float(a), INFINITY)) - double(float(a))
                            : std::nextafter(a, INFINITY) - a;
  return std::fabs(got - want) / ulp;
}
template <typename F, typename R>
void Check(const char* name, double lo, double hi, bool single, double maxUlp, std::uint64_t expected,
  F own, R reference, double floor = 0)
{
  Hash h;
  double worst = 0;
  state = 88172645463325252ull;
  for (int i = 0; i < 200000; ++i)
  {
    const double x = Uniform(lo, hi), y = Uniform(lo, hi);
    const double got = own(x, y), want = reference(x, y);
    if (single)
      h.Add(float(got));
    else
      h.Add(got);
    if (std::fabs(want) > floor)
      worst = std::max(worst, Ulps(got, want, single));
  }
  const bool ok = h.h == expected && worst <= maxUlp;
  std::printf("%s %-10s hash %016llx (recorded %016llx), largest error %.2f ulp (at most %.1f)\n",
    ok ? "ok  " : "FAIL", name, (unsigned long long)h.h, (unsigned long long)expected, worst, maxUlp);
  failures += ok ? 0 : 1;
}
}

int main()
{
  Check("acos", -1, 1, true, 1.5, 0xff2e4621248552e5ull, [](double x, double) { return double(sch_acos(float(x))); },
    [](double x, double) { return std::acos(double(float(x))); });
  Check("atan2", -2, 2, true, 2.5, 0x61dd271169e0caefull,
    [](double x, double y) { return double(sch_atan2(float(y), float(x))); },
    [](double x, double y) { return std::atan2(double(float(y)), double(float(x))); });
  Check("erfc", -9, 9, true, 10, 0xeb6dae3c81195b97ull, [](double x, double) { return double(sch_erfc(float(x))); },
    [](double x, double) { return std::erfc(double(float(x))); }, 1e-30);
  Check("exp", -87, 88, true, 1.5, 0x800f4f401e4101d7ull, [](double x, double) { return double(sch_exp(float(x))); },
    [](double x, double) { return std::exp(double(float(x))); });
  Check("cos", -1e3, 1e3, true, 2, 0xc2d1f46f263096d0ull, [](double x, double) { return double(sch_cos(float(x))); },
    [](double x, double) { return std::cos(double(float(x))); }, 1e-3);
  Check("atan_d", -20, 20, false, 2.5, 0x4d784749ef2a122bull, [](double x, double) { return sch_atan_d(x); },
    [](double x, double) { return std::atan(x); });
  Check("acos_d", -1, 1, false, 2.5, 0x8658f2a8024c9f31ull, [](double x, double) { return sch_acos_d(x); },
    [](double x, double) { return std::acos(x); });
  Check("hypot_d", -10, 10, false, 1.5, 0x38ce5b33c6f584a8ull, [](double x, double y) { return sch_hypot_d(x, y); },
    [](double x, double y) { return std::hypot(x, y); });
  Check("exp_d", -700, 700, false, 2, 0x5d170ac64b066323ull, [](double x, double) { return sch_exp_d(x); },
    [](double x, double) { return std::exp(x); });
  Check("tanh_d", -30, 30, false, 32, 0xe526859a5d397ed0ull, [](double x, double) { return sch_tanh_d(x); },
    [](double x, double) { return std::tanh(x); });
  std::printf("%d failures\n", failures);
  return failures ? 1 : 0;
}
