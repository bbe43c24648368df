#pragma once
// Flush-to-zero and denormals-are-zero on a thread while a guard lives: Embree's advice for every
// thread that builds or traces.
#include <pmmintrin.h>
#include <xmmintrin.h>

namespace kinray {

/// Flush-to-zero and denormals-are-zero for the lifetime of the guard on this thread (Embree's
/// advice for every thread that builds or traces); the caller's mode is restored afterwards so
/// that other code on the thread (the kinetic root solver) keeps IEEE denormals.
class FlushDenormals {
 public:
  FlushDenormals() : m_saved(_mm_getcsr()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
  ~FlushDenormals() { _mm_setcsr(m_saved); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned m_saved;
};

}  // namespace kinray
