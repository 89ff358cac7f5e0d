// libFuzzer target: any byte string given to parse_cut_spec (the `--cut` notation, and through
// `plane:` the `--plane` notation of parse_plane_spec) either parses into finite planes and
// lengths or is refused with std::invalid_argument. Anything else (a crash, another exception,
// a sanitizer report, a hang, a non-finite or unnormalised plane) is a finding.
// Built by tests/fuzz/CMakeLists.txt with clang -fsanitize=fuzzer,address,undefined.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "pieces/cut_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const double metres_per_unit : {1e-3, 1.0}) {
    try {
      const cutaway::CutSpec cut = cutaway::parse_cut_spec(text, metres_per_unit);
      const glm::dvec3 p = cut.plane.point, n = cut.plane.normal;
      const bool finite = std::isfinite(cut.thickness_m) && std::isfinite(cut.size_m) &&
                          std::isfinite(p.x + p.y + p.z) && std::isfinite(n.x + n.y + n.z);
      if (!finite) std::abort();
      if (cut.type == cutaway::CutType::Plane && std::fabs(glm::length(n) - 1) > 1e-9)
        std::abort();
    } catch (const std::invalid_argument&) {
      // Refused input: the expected outcome for almost every mutation.
    }
  }
  return 0;
}
