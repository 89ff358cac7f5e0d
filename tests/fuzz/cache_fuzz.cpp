// libFuzzer target: any bytes read back as a cut cache entry's payload (a cut object, or a
// scene's settled placements) either decode and pass or fail the checks a scene applies before
// use (cut_entry_check.h), or are refused as damaged (ByteStreamError). Anything else (a
// crash, another exception, a sanitizer report, an allocation over libFuzzer's memory limit,
// a hang) is a finding. The first byte picks the kind and the number of placements asked for;
// the rest is the payload. Built by tests/fuzz/CMakeLists.txt with clang
// -fsanitize=fuzzer,address,undefined.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "base/byte_stream.h"
#include "cache/cut_entry_check.h"
#include "cache/cut_entry_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view payload(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] & 1) {
    const size_t bodies = data[0] >> 1;
    if (const std::optional<cutaway::SettleResult> s = cutaway::decode_settled(payload, bodies)) {
      cutaway::Container board{cutaway::ContainerType::Board, 0, 0.4, 0.3, 0.02};
      const cutaway::Check usable =
          cutaway::check_cached_placements(s->placements, bodies, board, 0.2);
      if (!usable && usable.reason().empty()) std::abort();
    }
    return 0;
  }
  // A scene's assets holding the object's three given materials, as make_cut_entry's own.
  cutaway::SceneAssets assets;
  for (int k = 0; k < 3; ++k) assets.materials.push_back(assets.materials[0]);
  const cutaway::PieceMaterials given{1, 2, 3};
  try {
    cutaway::CachedCut cut = cutaway::decode_cut_payload(payload, assets, given);
    const cutaway::Check usable =
        cutaway::check_cached_cut(cut.pieces, cut.collision, !cut.collision.empty(), assets, 0.5);
    if (!usable && usable.reason().empty()) std::abort();
  } catch (const cutaway::ByteStreamError&) {
    // Damaged: the expected outcome for almost every mutation.
  }
  return 0;
}
