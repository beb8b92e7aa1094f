// SPDX-License-Identifier: BSD-3-Clause
// The engine's parallel interface on in-process ranks: every collective returns what its
// definition says (sums, extremes, broadcast, gather, all-to-all) on 1 to 4 ranks, failures agree
// on every rank, and collectives out of step end in an error, not a hang.
#include "SchlierenParallel.h"
#include "SchlierenTesting.h"

#include <atomic>
#include <mutex>

using namespace schlieren;

int main()
{
  for (int n = 1; n <= 4; ++n)
  {
    std::mutex m;
    int bad = 0;
    auto expect = [&](bool ok) {
      if (!ok)
      {
        std::lock_guard<std::mutex> lock(m);
        ++bad;
      }
    };
    RunInProcessRanks(n, [&](Parallel& p) {
      const int r = p.Rank();
      expect(p.Size() == n);
      // sum of 1..n, min 1, max n, element-wise
      double v[3] = { r + 1.0, r + 1.0, r + 1.0 };
      p.Sum(v, 1);
      p.Min(v + 1, 1);
      p.Max(v + 2, 1);
      expect(v[0] == n * (n + 1) / 2.0 && v[1] == 1.0 && v[2] == n);
      expect(p.AllOk(true) && !p.AllOk(r != n - 1));
      // broadcast from the last rank
      expect(p.BroadcastString(r == n - 1 ? "from the last" : "", n - 1) == "from the last");
      // gather in rank order
      std::vector<std::string> all = p.AllGatherStrings(std::string(r + 1, 'a' + r));
      bool order = static_cast<int>(all.size()) == n;
      for (int q = 0; order && q < n; ++q)
        order = all[q] == std::string(q + 1, 'a' + q);
      expect(order);
      // all-to-all: rank r sends rank q the bytes {r, q} (and nothing to q == r + 1)
      std::vector<std::vector<char>> out(n);
      for (int q = 0; q < n; ++q)
        if (q != r + 1)
          out[q] = { static_cast<char>(r), static_cast<char>(q) };
      std::vector<std::vector<char>> in = p.Exchange(out);
      bool routed = static_cast<int>(in.size()) == n;
      for (int q = 0; routed && q < n; ++q)
        routed = (r == q + 1) ? in[q].empty()
                              : (in[q].size() == 2 && in[q][0] == q && in[q][1] == r);
      expect(routed);
      // agreement: no failure; then rank n - 1 fails and every rank learns its message
      expect(p.Failure("").empty());
      const std::string f = p.Failure(r == n - 1 ? "bad piece" : "");
      expect(r == n - 1 ? f == "bad piece"
                        : f == "another rank (" + std::to_string(n - 1) + ") failed: bad piece");
    });
    CHECK(bad == 0, "collectives on " + std::to_string(n) + " in-process ranks");
  }

  // a rank that throws: the others' next collective throws too, and the first error comes back
  bool threw = false;
  try
  {
    RunInProcessRanks(3, [](Parallel& p) {
      if (p.Rank() == 1)
        throw Error("rank 1 broke");
      p.Sum(1.0);
    });
  }
  catch (const Error& e)
  {
    threw = std::string(e.what()) == "rank 1 broke";
  }
  CHECK(threw, "a rank's error is rethrown, the others do not hang");

  // collectives out of step (rank 0 calls one more): an error, not a hang
  threw = false;
  try
  {
    RunInProcessRanks(2, [](Parallel& p) {
      p.Sum(1.0);
      if (p.Rank() == 0)
        p.Sum(1.0);
    });
  }
  catch (const Error& e)
  {
    threw = std::string(e.what()).find("returned while") != std::string::npos;
  }
  CHECK(threw, "a collective out of step ends in an error");

  return schtest::Finish();
}
