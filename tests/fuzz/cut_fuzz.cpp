// libFuzzer target: any byte string given to parse_cut_spec (the `--cut` notation, and through
// `plane:` the `--plane` notation of parse_plane_spec) either parses into finite planes and
// lengths or is refused with a reason (an Outcome without a value). Anything else (a crash, an
// exception, a sanitizer report, a hang, a non-finite or unnormalised plane) is a finding. Built by
// tests/fuzz/CMakeLists.txt with clang -fsanitize=fuzzer,address,undefined.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <glm/geometric.hpp>

#include "io/cut_notation.h"
#include "pieces/cut_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const double metres_per_unit : {1e-3, 1.0}) {
    const cutaway::Outcome<cutaway::CutSpec> parsed =
        cutaway::parse_cut_spec(text, metres_per_unit);
    if (!parsed) {
      // Refused input: the expected outcome for almost every mutation; it says why.
      if (parsed.reason().empty()) std::abort();
      continue;
    }
    const cutaway::CutSpec& cut = *parsed;
    const glm::dvec3 p = cut.plane.point, n = cut.plane.normal;
    const bool finite = std::isfinite(cut.thickness_m) && std::isfinite(cut.size_m) &&
                        std::isfinite(p.x + p.y + p.z) && std::isfinite(n.x + n.y + n.z);
    if (!finite) std::abort();
    if (cut.type == cutaway::CutType::Plane && std::fabs(glm::length(n) - 1) > 1e-9) std::abort();
  }
  return 0;
}
