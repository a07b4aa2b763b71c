// A replacement of the global allocator (malloc family and every operator new) that counts calls,
// for the tests that prove a real-time path allocates nothing and for mrqp-run's
// `allocations_in_loop` (summary.json). Two counts: every allocation of the process, and those of
// the threads that armed the counter (the loop thread of mrqp-run; a log-draining thread is not
// counted). Link the object library mrqp_counting_allocator (tests/support) into the program (not
// into a sanitizer build: the sanitizers replace the allocator themselves).
#pragma once

#include <Eigen/Core>

namespace mrqp::testing {

/// Heap allocations made so far by this process.
long allocationCount() noexcept;

/// Counting of the calling thread's allocations into armedAllocationCount() starts (true) or
/// stops (false).
void armThreadCounter(bool on) noexcept;
/// Allocations made so far by threads while they had the counter armed.
long armedAllocationCount() noexcept;

/// Allocations made by `body`, with Eigen's run-time allocation check armed when the program is
/// compiled with EIGEN_RUNTIME_NO_MALLOC (an Eigen heap allocation then aborts).
template <class F>
long allocationsIn(F&& body) {
#ifdef EIGEN_RUNTIME_NO_MALLOC
  Eigen::internal::set_is_malloc_allowed(false);
#endif
  const long before = allocationCount();
  body();
  const long after = allocationCount();
#ifdef EIGEN_RUNTIME_NO_MALLOC
  Eigen::internal::set_is_malloc_allowed(true);
#endif
  return after - before;
}

}  // namespace mrqp::testing
