// libFuzzer target: any byte string given to parse_scene either parses or is refused with an
// InputError. Anything else (a crash, another exception, a sanitizer report, a hang) is a
// finding. Template names resolve from scenes/ as for a shipped scene (the files are not read).
// Built by tests/fuzz/CMakeLists.txt with clang -fsanitize=fuzzer,address,undefined.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "base/error.h"
#include "io/scene_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    cutaway::parse_scene(text, CUTAWAY_FUZZ_SCENE_FILE);
  } catch (const cutaway::InputError&) {
    // Refused input: the expected outcome for almost every mutation.
  }
  return 0;
}
