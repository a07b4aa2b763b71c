// The one assertion of the fuzz harnesses (tests/fuzz): a property of a reader's output that must
// hold for every input. A violation prints what failed and aborts, which libFuzzer reports as a
// crash and saves the input (docs/robustness.md, "Fuzzing").
#pragma once

#include <cstdio>
#include <cstdlib>

#define MRQP_FUZZ_CHECK(cond)                                                                 \
  do {                                                                                        \
    if (!(cond)) {                                                                            \
      std::fprintf(stderr, "%s:%d: fuzz property violated: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                           \
    }                                                                                         \
  } while (0)
