// Which sources this build was made from.
#pragma once

namespace cutaway {

/// The SHA-256 (64 hex digits) of the sources that decide what cutaway writes: generator/,
/// render/ and shaders/, fixed when the build runs (cmake/source_fingerprint.cmake). Builds
/// of the same sources agree on any machine; any change to them, even to a comment, gives
/// another value. Batch fingerprints include it, so that a batch resumed after an upgrade
/// remakes its assets instead of keeping ones the old code made (doc/batch-format.md).
const char* source_fingerprint();

}  // namespace cutaway
