// libFuzzer target: any bytes given as a `mesh` surface's PLY file are either imported or refused
// with an InputError, quickly and in little memory: check_ply (the guard in front of OpenMesh),
// then OpenMesh's reader (read_mesh_file), then the DS surface (mesh_surface). Anything else (a
// crash, another exception, a sanitizer report, a hang, a large allocation) is a finding. Built by
// tests/fuzz/CMakeLists.txt with clang -fsanitize=fuzzer,address,undefined.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include "base/error.h"
#include "io/mesh_file.h"
#include "io/ply_guard.h"
#include "model/mesh_surface.h"
#include "model/template.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The importer reads a file: one per fuzzing process, rewritten for every input.
  static const std::string file = (std::filesystem::temp_directory_path() /
                                   ("cutaway_ply_fuzz_" + std::to_string(::getpid()) + ".ply"))
                                      .string();
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());

  cutaway::Template tmpl;
  tmpl.metres_per_unit = 1e-3;
  tmpl.symmetry = cutaway::Symmetry::None;
  cutaway::SurfaceSpec spec;
  spec.name = "fuzz";
  spec.kind = cutaway::SurfaceKind::Mesh;
  spec.is_skin = size % 2 == 0;  // a skin must be closed: both paths, chosen by the input
  spec.mesh_file = file;
  spec.mesh_loc = cutaway::FileLoc{"fuzz.yaml", 1, 1};
  spec.path = "surfaces[0]";
  try {
    cutaway::check_ply(bytes, spec.mesh_loc, "surfaces[0].file");
    spec.mesh = std::make_shared<const cutaway::MeshData>(
        cutaway::read_mesh_file(file, spec.mesh_loc, "surfaces[0].file"));
    cutaway::mesh_surface(spec, tmpl);
  } catch (const cutaway::InputError&) {
    // Refused input: the expected outcome for most mutations.
  }
  return 0;
}
