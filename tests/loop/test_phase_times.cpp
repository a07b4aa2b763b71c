// loop::PhaseTimes (control/loop/phase_times.hpp): per-phase count, mean and largest time against a
// direct computation over the recorded durations, and laps of the monotonic clock against
// std::chrono::steady_clock around the same busy waits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <random>
#include <vector>

#include "loop/phase_times.hpp"

using mrqp::drivers::TimeNs;

TEST_CASE("loop: phase times against a direct computation", "[loop][timing]") {
  mrqp::loop::PhaseTimes<3> pt;
  std::mt19937 rng(7);
  std::uniform_int_distribution<TimeNs> d(0, 5000000);
  std::vector<TimeNs> rec[3];
  for (int k = 0; k < 1000; ++k) {
    const auto p = static_cast<std::size_t>(k % 3 == 2 ? 2 : k % 2);
    const TimeNs ns = d(rng);
    pt.add(p, ns);
    rec[p].push_back(ns);
  }
  for (std::size_t p = 0; p < 3; ++p) {
    CHECK(pt.count(p) == rec[p].size());
    CHECK(pt.max(p) == *std::max_element(rec[p].begin(), rec[p].end()));
    const double mean = static_cast<double>(std::accumulate(rec[p].begin(), rec[p].end(), TimeNs{0})) /
                        static_cast<double>(rec[p].size());
    CHECK(pt.mean(p) == Approx(mean).epsilon(1e-12));
  }
  pt.add(3, 1);  // no such phase: ignored
  CHECK(pt.count(3) == 0u);
  CHECK(mrqp::loop::PhaseTimes<2>().mean(0) == 0.0);
}

TEST_CASE("loop: phase times from laps of the clock", "[loop][timing]") {
  using clock = std::chrono::steady_clock;
  auto busy = [](std::chrono::microseconds us) {
    const auto end = clock::now() + us;
    while (clock::now() < end) {}
  };
  mrqp::loop::PhaseTimes<2> pt;
  const auto t0 = clock::now();
  pt.begin();
  busy(std::chrono::microseconds(300));
  pt.lap(0);
  const auto t1 = clock::now();
  busy(std::chrono::microseconds(100));
  pt.lap(1);
  const auto t2 = clock::now();
  const auto ns = [](clock::duration x) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(x).count();
  };
  CHECK(pt.max(0) >= 300000);
  CHECK(pt.max(1) >= 100000);
  // Both phases together within what the other clock saw around them.
  CHECK(pt.max(0) + pt.max(1) <= ns(t2 - t0));
  CHECK(pt.max(0) <= ns(t1 - t0));
}
