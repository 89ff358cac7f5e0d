// Content hashes: FNV-1a (Fowler, Noll, Vo), as manifests and fingerprints write them, and
// CRC-32, the check of the cut cache's entries.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cutaway {

/// FNV-1a, 64 bits: the content hash of a written file in manifests (so that a batch can be
/// checked against another run without comparing the files themselves) and of a template file
/// in asset fingerprints.
/// Continues from `hash` (the value of the bytes before, or kFnv1a64Start): fnv1a64(b,
/// fnv1a64(a)) == fnv1a64(a + b), so a file can be hashed a piece at a time.
inline constexpr uint64_t kFnv1a64Start = 0xcbf29ce484222325ULL;
uint64_t fnv1a64(std::string_view bytes, uint64_t hash = kFnv1a64Start);

/// CRC-32 (ISO-HDLC, as zlib, PNG and gzip compute it) of `bytes`, continuing from `crc` (0
/// to start): crc32(b, crc32(a)) == crc32(a + b). zlib's table-driven code checks a gigabyte
/// in about a fifth of a second, seven times as fast as fnv1a64's chain of multiplications;
/// a check of damaged data, not a content hash (use fnv1a64 where the value is written down).
uint32_t crc32(std::string_view bytes, uint32_t crc = 0);

/// `hash` as manifests write it: 16 lower-case hex digits.
std::string hex64(uint64_t hash);

}  // namespace cutaway
