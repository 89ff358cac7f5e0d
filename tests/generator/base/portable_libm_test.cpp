// The portable libm (base/portable_libm.h): every call in the process, a shared library's
// included, reaches this program's definitions, and they compute SLEEF's bits.
#include "base/portable_libm.h"

#include <dlfcn.h>

#include <cmath>

#include <gtest/gtest.h>
#include <sleef.h>

namespace cutaway {
namespace {

TEST(PortableLibm, EveryFunctionResolvesToThisProgramsDefinition) {
  const Check libm = check_portable_libm();
  EXPECT_TRUE(libm) << libm.reason();
  EXPECT_EQ(kPortableLibmFunctionCount, 50);
}

TEST(PortableLibm, CallsComputeSleefsPureCBits) {
  // Through the dynamic linker, as Bullet's and Embree's calls go.
  using Unary = double (*)(double);
  using UnaryFloat = float (*)(float);
  const auto sin_found = reinterpret_cast<Unary>(dlsym(RTLD_DEFAULT, "sin"));
  const auto powf_found = reinterpret_cast<float (*)(float, float)>(dlsym(RTLD_DEFAULT, "powf"));
  const auto acosf_found = reinterpret_cast<UnaryFloat>(dlsym(RTLD_DEFAULT, "acosf"));
  ASSERT_TRUE(sin_found && powf_found && acosf_found);
  for (double x : {0.1, 1.0, 2.5, 1e3, -7.25, 123456.789}) {
    EXPECT_EQ(sin_found(x), Sleef_sind1_u10purec(x)) << x;
    volatile double v = x;  // a call the compiler cannot fold
    EXPECT_EQ(std::exp(v * 0.01), Sleef_expd1_u10purec(x * 0.01)) << x;
    EXPECT_EQ(std::atan2(v, 3.0), Sleef_atan2d1_u10purec(x, 3.0)) << x;
  }
  for (float x : {0.1f, 0.5f, 0.99f}) EXPECT_EQ(acosf_found(x), Sleef_acosf1_u10purec(x)) << x;
  EXPECT_EQ(powf_found(1.7f, 2.2f), Sleef_powf1_u10purec(1.7f, 2.2f));
}

}  // namespace
}  // namespace cutaway
