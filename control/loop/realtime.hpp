// Real-time set-up of the loop's process and thread (docs/loop.md, "Real time"): memory locked
// (mlockall), the heap kept (no trimming, no mmap'd blocks) and pre-faulted, the stack pre-faulted,
// SCHED_FIFO and a CPU of its own when permitted. Each step that could not be had is reported
// with the reason; none of them is fatal. Set-up only.
#pragma once

#include <string>
#include <vector>

namespace mrqp::loop {

struct RealtimeOptions {
  int priority = 80;  ///< SCHED_FIFO priority
  int cpu = -1;       ///< -1: the last CPU of the machine
  std::size_t stack_bytes = 512 * 1024;
  std::size_t heap_bytes = 64 * 1024 * 1024;
};

struct RealtimeReport {
  bool memory_locked = false;
  bool heap_prefaulted = false;
  bool stack_prefaulted = false;
  bool fifo = false;
  bool affinity = false;
  int cpu = -1;
  std::vector<std::string> messages;  ///< one line per step that could not be had (or was)
};

/// Applies the real-time set-up to the calling thread and the process.
RealtimeReport setupRealtime(const RealtimeOptions& options = RealtimeOptions{});

}  // namespace mrqp::loop
