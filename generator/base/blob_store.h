// A store of bytes under keys, kept between runs (the cut cache gives one: CutCache::
// blob_store), for steps below the cache that keep slow results: KTX2 textures
// (ktx2_texture.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace cutaway {

/// `load` gives the bytes stored under a key or none; `store` keeps bytes under a key;
/// `discard` removes an entry that failed its reader's check and says why. What `load` gives
/// is untrusted input: its reader checks it.
struct BlobStore {
  std::function<std::optional<std::string>(std::string_view key)> load;
  std::function<void(std::string_view key, std::string_view bytes)> store;
  std::function<void(std::string_view key, const std::string& reason)> discard;
};

}  // namespace cutaway
