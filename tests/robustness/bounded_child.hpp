// Running a piece of code in a child process with its address space limited (RLIMIT_AS) and a
// time limit, for the tests that prove a reader refuses hostile input before allocating from it
// or looping on it: a reader that allocated n×n doubles from a 27-byte header, or looped, would
// get std::bad_alloc or be killed instead of answering. Under the sanitizers (which reserve
// terabytes of address space) the limit is left out and only the time limit applies.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

namespace mrqp::testing {

/// How the child ended.
enum class ChildEnd { ReturnedTrue, ReturnedFalse, OutOfMemory, Exception, Killed };

/// Runs `body` (returning bool) in a child limited to `extra_mb` megabytes of address space above
/// what the test process uses now, and to `seconds` of wall time.
template <class F>
ChildEnd runBounded(F&& body, long extra_mb = 256, unsigned seconds = 20) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
#ifndef MRQP_SANITIZED
    long pages = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
      std::fclose(f);
    }
    const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) +
                         static_cast<rlim_t>(extra_mb) * 1024 * 1024;
    const rlimit rl{limit, limit};
    setrlimit(RLIMIT_AS, &rl);
#else
    (void)extra_mb;
#endif
    alarm(seconds);
    int code = 4;
    try {
      code = body() ? 0 : 1;
    } catch (const std::bad_alloc&) {
      code = 2;
    } catch (const std::exception&) {
      code = 3;
    }
    _exit(code);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return ChildEnd::Killed;
  switch (WEXITSTATUS(status)) {
    case 0:
      return ChildEnd::ReturnedTrue;
    case 1:
      return ChildEnd::ReturnedFalse;
    case 2:
      return ChildEnd::OutOfMemory;
    case 3:
      return ChildEnd::Exception;
    default:
      return ChildEnd::Killed;
  }
}

}  // namespace mrqp::testing
