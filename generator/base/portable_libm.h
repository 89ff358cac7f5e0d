// The C math library's transcendental functions with the same bits on every CPU
// (doc/architecture.md, Determinism: same bits on any CPU).
//
// glibc picks its sin, cos, exp, log, pow, atan2, ... per CPU when it loads (FMA and AVX2
// variants where the CPU has them, SSE2 ones elsewhere), and their last bits differ; that was
// enough to change a cut's mesh. portable_libm.cpp defines those functions itself, in the
// executable, as SLEEF's pure-C scalar versions (1.0 ULP; no FMA, no run-time dispatch), and
// exports them: the dynamic linker then binds every call in the process to them, ours and those
// inside Bullet, Embree and Mesa alike (an executable's definition comes first in symbol
// lookup). Correctly rounded functions (sqrt, fma, floor, round, fmod, ldexp, ...) are left to
// the C library: they give the same bits everywhere already.
#pragma once

#include "base/outcome.h"

namespace cutaway {

/// The names this program defines in place of the C library's (double and float versions).
/// The build exports each of them from every executable (generator/CMakeLists.txt).
extern const char* const kPortableLibmFunctions[];
/// The number of names in kPortableLibmFunctions.
extern const int kPortableLibmFunctionCount;

/// Passes when every name of kPortableLibmFunctions resolves, process-wide (as a shared
/// library's call would), to this program's definition; otherwise fails naming those that do
/// not, comma-separated: then some library's calls still reach the C library's per-CPU versions.
Check check_portable_libm();

}  // namespace cutaway
