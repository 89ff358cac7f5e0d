// FNV-1a content hashes (Fowler, Noll, Vo), as manifests and fingerprints write them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cutaway {

/// FNV-1a, 64 bits: the content hash of a written file in manifests (so that a batch can be
/// checked against another run without comparing the files themselves) and of a template file
/// in asset fingerprints.
uint64_t fnv1a64(std::string_view bytes);

/// `hash` as manifests write it: 16 lower-case hex digits.
std::string hex64(uint64_t hash);

}  // namespace cutaway
