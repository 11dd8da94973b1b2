// Subnormal floats (below 2.2e-308) cost x86 cores tens of times a normal operation. A body
// that friction has brought to rest keeps a velocity and a friction state that decay
// geometrically through them for thousands of steps (a 20 s run of a puck at rest was 4x
// slower than it should be). They carry no physics: while this guard lives, the thread's
// arithmetic flushes them to zero (SSE flush-to-zero and denormals-are-zero); the previous
// mode comes back at its end. Elsewhere than x86 it does nothing.
#pragma once

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace stiction::core {

class FlushSubnormals {
 public:
#if defined(__SSE2__)
  FlushSubnormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
  ~FlushSubnormals() { _mm_setcsr(saved_); }
#else
  FlushSubnormals() = default;
#endif
  FlushSubnormals(const FlushSubnormals&) = delete;
  FlushSubnormals& operator=(const FlushSubnormals&) = delete;

 private:
#if defined(__SSE2__)
  static constexpr unsigned kFlushToZero = 0x8000;     // MXCSR bit 15
  static constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit 6
  unsigned saved_;
#endif
};

}  // namespace stiction::core
