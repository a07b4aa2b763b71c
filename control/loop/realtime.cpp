// Real-time set-up (see realtime.hpp).
#include "loop/realtime.hpp"

#include <malloc.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace mrqp::loop {

namespace {

__attribute__((noinline)) void touchStack(std::size_t bytes) {
  // A large local array written page by page: the pages stay mapped (and locked) afterwards.
  constexpr std::size_t kChunk = 64 * 1024;
  unsigned char block[kChunk];
  for (std::size_t i = 0; i < kChunk; i += 4096) block[i] = static_cast<unsigned char>(i);
  // The compiler must believe the block is used: pass it through an opaque barrier.
  asm volatile("" : : "r"(block) : "memory");
  if (bytes > kChunk) touchStack(bytes - kChunk);
}

std::string why(int err) { return std::strerror(err); }

}  // namespace

RealtimeReport setupRealtime(const RealtimeOptions& o) {
  RealtimeReport r;
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    r.memory_locked = true;
    r.messages.push_back("memory locked (mlockall)");
  } else {
    r.messages.push_back("memory NOT locked: mlockall: " + why(errno) +
                         " (needs CAP_IPC_LOCK or a higher RLIMIT_MEMLOCK, e.g. ulimit -l unlimited)");
  }
  // Keep freed heap memory in the process and never serve allocations from fresh mmap'd blocks:
  // the pages faulted in now stay.
  const bool kept = mallopt(M_TRIM_THRESHOLD, -1) == 1 && mallopt(M_MMAP_MAX, 0) == 1;
  if (void* p = std::malloc(o.heap_bytes)) {
    auto* bytes = static_cast<volatile unsigned char*>(p);
    const long page = sysconf(_SC_PAGESIZE);
    for (std::size_t i = 0; i < o.heap_bytes; i += static_cast<std::size_t>(page > 0 ? page : 4096))
      bytes[i] = 0;
    std::free(p);
    r.heap_prefaulted = kept;
    r.messages.push_back(kept ? "heap pre-faulted (" + std::to_string(o.heap_bytes >> 20) +
                                    " MiB, no trimming)"
                              : "heap pre-faulted, but malloc may still trim it (mallopt refused)");
  } else {
    r.messages.push_back("heap NOT pre-faulted: no memory for " + std::to_string(o.heap_bytes >> 20) +
                         " MiB");
  }
  touchStack(o.stack_bytes);
  r.stack_prefaulted = true;
  r.messages.push_back("stack pre-faulted (" + std::to_string(o.stack_bytes >> 10) + " KiB)");

  sched_param sp{};
  sp.sched_priority = o.priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (err == 0) {
    r.fifo = true;
    r.messages.push_back("SCHED_FIFO priority " + std::to_string(o.priority));
  } else {
    r.messages.push_back("SCHED_FIFO NOT set: " + why(err) +
                         " (needs CAP_SYS_NICE or an RLIMIT_RTPRIO >= " + std::to_string(o.priority) + ")");
  }
  const long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
  r.cpu = o.cpu >= 0 ? o.cpu : static_cast<int>(ncpu > 0 ? ncpu - 1 : 0);
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<std::size_t>(r.cpu), &set);
  const int aerr = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
  if (aerr == 0) {
    r.affinity = true;
    r.messages.push_back("pinned to CPU " + std::to_string(r.cpu));
  } else {
    r.messages.push_back("CPU affinity NOT set (CPU " + std::to_string(r.cpu) + "): " + why(aerr));
  }
  return r;
}

}  // namespace mrqp::loop
