// mrqp-run's allocation counter: the program replaces the global allocator (malloc family and
// every operator new) with one that counts the allocations of the thread that armed it — the
// loop thread — so summary.json's allocations_in_loop is measured, not assumed. The log-draining
// thread is not counted.
#pragma once

namespace mrqp::run {

/// Counting starts (true) or stops (false) for the calling thread.
void armAllocationCounter(bool on) noexcept;
/// Allocations counted so far.
long countedAllocations() noexcept;

}  // namespace mrqp::run
