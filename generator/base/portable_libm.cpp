#include "base/portable_libm.h"

#include <dlfcn.h>
#include <sleef.h>

#include <string>

// The definitions are plain C functions with the C library's names and signatures (noexcept,
// as glibc declares them for C++). Each forwards to SLEEF's pure-C scalar version with a 1.0
// ULP bound: "purec" is compiled without FMA and is never swapped for another variant at run
// time, so it computes the same bits on every x86-64 CPU.
extern "C" {

#define CUTAWAY_PORTABLE_UNARY(name, type, sleef) \
  type name(type x) noexcept { return sleef(x); }
#define CUTAWAY_PORTABLE_BINARY(name, type, sleef) \
  type name(type x, type y) noexcept { return sleef(x, y); }

CUTAWAY_PORTABLE_UNARY(sin, double, Sleef_sind1_u10purec)
CUTAWAY_PORTABLE_UNARY(cos, double, Sleef_cosd1_u10purec)
CUTAWAY_PORTABLE_UNARY(tan, double, Sleef_tand1_u10purec)
CUTAWAY_PORTABLE_UNARY(asin, double, Sleef_asind1_u10purec)
CUTAWAY_PORTABLE_UNARY(acos, double, Sleef_acosd1_u10purec)
CUTAWAY_PORTABLE_UNARY(atan, double, Sleef_atand1_u10purec)
CUTAWAY_PORTABLE_BINARY(atan2, double, Sleef_atan2d1_u10purec)
CUTAWAY_PORTABLE_UNARY(sinh, double, Sleef_sinhd1_u10purec)
CUTAWAY_PORTABLE_UNARY(cosh, double, Sleef_coshd1_u10purec)
CUTAWAY_PORTABLE_UNARY(tanh, double, Sleef_tanhd1_u10purec)
CUTAWAY_PORTABLE_UNARY(asinh, double, Sleef_asinhd1_u10purec)
CUTAWAY_PORTABLE_UNARY(acosh, double, Sleef_acoshd1_u10purec)
CUTAWAY_PORTABLE_UNARY(atanh, double, Sleef_atanhd1_u10purec)
CUTAWAY_PORTABLE_UNARY(exp, double, Sleef_expd1_u10purec)
CUTAWAY_PORTABLE_UNARY(exp2, double, Sleef_exp2d1_u10purec)
CUTAWAY_PORTABLE_UNARY(exp10, double, Sleef_exp10d1_u10purec)
CUTAWAY_PORTABLE_UNARY(expm1, double, Sleef_expm1d1_u10purec)
CUTAWAY_PORTABLE_UNARY(log, double, Sleef_logd1_u10purec)
CUTAWAY_PORTABLE_UNARY(log2, double, Sleef_log2d1_u10purec)
CUTAWAY_PORTABLE_UNARY(log10, double, Sleef_log10d1_u10purec)
CUTAWAY_PORTABLE_UNARY(log1p, double, Sleef_log1pd1_u10purec)
CUTAWAY_PORTABLE_BINARY(pow, double, Sleef_powd1_u10purec)
CUTAWAY_PORTABLE_UNARY(cbrt, double, Sleef_cbrtd1_u10purec)
CUTAWAY_PORTABLE_BINARY(hypot, double, Sleef_hypotd1_u05purec)

CUTAWAY_PORTABLE_UNARY(sinf, float, Sleef_sinf1_u10purec)
CUTAWAY_PORTABLE_UNARY(cosf, float, Sleef_cosf1_u10purec)
CUTAWAY_PORTABLE_UNARY(tanf, float, Sleef_tanf1_u10purec)
CUTAWAY_PORTABLE_UNARY(asinf, float, Sleef_asinf1_u10purec)
CUTAWAY_PORTABLE_UNARY(acosf, float, Sleef_acosf1_u10purec)
CUTAWAY_PORTABLE_UNARY(atanf, float, Sleef_atanf1_u10purec)
CUTAWAY_PORTABLE_BINARY(atan2f, float, Sleef_atan2f1_u10purec)
CUTAWAY_PORTABLE_UNARY(sinhf, float, Sleef_sinhf1_u10purec)
CUTAWAY_PORTABLE_UNARY(coshf, float, Sleef_coshf1_u10purec)
CUTAWAY_PORTABLE_UNARY(tanhf, float, Sleef_tanhf1_u10purec)
CUTAWAY_PORTABLE_UNARY(asinhf, float, Sleef_asinhf1_u10purec)
CUTAWAY_PORTABLE_UNARY(acoshf, float, Sleef_acoshf1_u10purec)
CUTAWAY_PORTABLE_UNARY(atanhf, float, Sleef_atanhf1_u10purec)
CUTAWAY_PORTABLE_UNARY(expf, float, Sleef_expf1_u10purec)
CUTAWAY_PORTABLE_UNARY(exp2f, float, Sleef_exp2f1_u10purec)
CUTAWAY_PORTABLE_UNARY(exp10f, float, Sleef_exp10f1_u10purec)
CUTAWAY_PORTABLE_UNARY(expm1f, float, Sleef_expm1f1_u10purec)
CUTAWAY_PORTABLE_UNARY(logf, float, Sleef_logf1_u10purec)
CUTAWAY_PORTABLE_UNARY(log2f, float, Sleef_log2f1_u10purec)
CUTAWAY_PORTABLE_UNARY(log10f, float, Sleef_log10f1_u10purec)
CUTAWAY_PORTABLE_UNARY(log1pf, float, Sleef_log1pf1_u10purec)
CUTAWAY_PORTABLE_BINARY(powf, float, Sleef_powf1_u10purec)
CUTAWAY_PORTABLE_UNARY(cbrtf, float, Sleef_cbrtf1_u10purec)
CUTAWAY_PORTABLE_BINARY(hypotf, float, Sleef_hypotf1_u05purec)

#undef CUTAWAY_PORTABLE_UNARY
#undef CUTAWAY_PORTABLE_BINARY

// GCC turns a sin and a cos of the same argument into one sincos call.
void sincos(double x, double* s, double* c) noexcept {
  const Sleef_double_2 r = Sleef_sincosd1_u10purec(x);
  *s = r.x;
  *c = r.y;
}
void sincosf(float x, float* s, float* c) noexcept {
  const Sleef_float_2 r = Sleef_sincosf1_u10purec(x);
  *s = r.x;
  *c = r.y;
}

}  // extern "C"

namespace cutaway {

const char* const kPortableLibmFunctions[] = {
    "sin",    "cos",    "tan",   "asin",   "acos",   "atan",   "atan2",  "sinh",  "cosh",
    "tanh",   "asinh",  "acosh", "atanh",  "exp",    "exp2",   "exp10",  "expm1", "log",
    "log2",   "log10",  "log1p", "pow",    "cbrt",   "hypot",  "sincos", "sinf",  "cosf",
    "tanf",   "asinf",  "acosf", "atanf",  "atan2f", "sinhf",  "coshf",  "tanhf", "asinhf",
    "acoshf", "atanhf", "expf",  "exp2f",  "exp10f", "expm1f", "logf",   "log2f", "log10f",
    "log1pf", "powf",   "cbrtf", "hypotf", "sincosf"};
const int kPortableLibmFunctionCount =
    static_cast<int>(sizeof(kPortableLibmFunctions) / sizeof(kPortableLibmFunctions[0]));

Check check_portable_libm() {
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&check_portable_libm), &self) == 0)
    return Check::none("dladdr failed");
  std::string misses;
  for (const char* name : kPortableLibmFunctions) {
    Dl_info found{};
    void* address = dlsym(RTLD_DEFAULT, name);
    if (!address || dladdr(address, &found) == 0 || found.dli_fbase != self.dli_fbase)
      misses += (misses.empty() ? "" : ", ") + std::string(name);
  }
  if (misses.empty()) return {};
  return Check::none("not this program's: " + misses);
}

}  // namespace cutaway
