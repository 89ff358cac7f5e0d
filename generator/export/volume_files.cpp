#include "export/volume_files.h"

#include "export/vdb_export.h"
#include "export/volume_flipbook.h"

namespace cutaway {

Outcome<std::vector<NamedFile>> volume_files(const InteriorVolume& volume, const std::string& stem,
                                             const std::string& name, int64_t seed, bool with_vdb) {
  Outcome<VolumeFlipbooks> books = encode_flipbooks(volume);
  if (!books) return Outcome<std::vector<NamedFile>>::none(books.reason());
  const VolumeFileNames names{stem + ".colour.png", stem + ".structure.png", stem + ".material.png",
                              with_vdb ? stem + ".vdb" : ""};
  std::vector<NamedFile> files;
  files.emplace_back(stem + ".json", volume_sidecar(volume, name, seed, names).dump(2) + "\n");
  files.emplace_back(names.colour, std::move(books->colour));
  files.emplace_back(names.structure, std::move(books->structure));
  files.emplace_back(names.material, std::move(books->material));
  if (with_vdb) files.emplace_back(names.vdb, encode_vdb(volume, name, seed));
  return files;
}

}  // namespace cutaway
