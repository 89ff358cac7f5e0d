#include "pieces/pieces.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "base/parallel_chunks.h"
#include "base/timer.h"
#include "diffusion/shared_batches.h"
#include "pieces/clip_mesh.h"
#include "pieces/manifold_check.h"
#include "pieces/rigid_stones.h"
#include "pieces/seam_stitch.h"

namespace cutaway {

namespace {

/// A DS surface as a shaded mesh showing one side's colour; `facing_back` turns its back side
/// outwards (reversed winding and normals).
ShadedMesh shaded_surface(const DsSurface& surface, bool show_front, bool facing_back) {
  ShadedMesh out;
  const std::vector<glm::dvec3> normals = vertex_normals(surface.mesh);
  for (auto vh : surface.mesh.vertices()) {
    const auto& p = surface.mesh.point(vh);
    const auto& data = surface.mesh.data(vh);
    const auto& c = show_front ? data.front : data.back;
    const auto& m = show_front ? data.material_front : data.material_back;
    out.position.emplace_back(p[0], p[1], p[2]);
    out.normal.push_back(normals[vh.idx()]);
    out.colour.emplace_back(c[0], c[1], c[2]);
    out.material.emplace_back(m[0], m[1]);
    out.param.emplace_back(data.param[0], data.param[1]);
  }
  for (auto fh : surface.mesh.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto vh : surface.mesh.fv_range(fh)) t[k++] = static_cast<unsigned>(vh.idx());
    out.triangle.push_back(t);
  }
  if (facing_back) flip(out);
  return out;
}

/// The part of `mesh` inside `cell`.
ShadedMesh clip_to_cell(ShadedMesh mesh, const CutCells& cells, const Cell& cell) {
  for (const CellFace& f : cell.faces) {
    if (mesh.triangle.empty()) break;
    mesh = clip_to_half_space(mesh, cells.planes[f.plane], !f.outward);
  }
  return mesh;
}

/// The triangles of `section` in `cell` (by centroid), facing out of the cell through `face`.
ShadedMesh cap_in_cell(const CrossSection& section, const CutCells& cells, const Cell& cell,
                       const CellFace& face) {
  ShadedMesh out;
  std::vector<unsigned> remap(section.position.size(), ~0u);
  const glm::dvec3 normal = face.outward ? section.plane.normal : -section.plane.normal;
  for (glm::uvec3 t : section.triangle) {
    const glm::dvec3 c =
        (section.position[t[0]] + section.position[t[1]] + section.position[t[2]]) / 3.0;
    if (!in_cell(cells, cell, c, face.plane)) continue;
    for (int k = 0; k < 3; ++k) {
      if (remap[t[k]] == ~0u) {
        out.position.push_back(section.position[t[k]]);
        out.normal.push_back(normal);
        out.colour.push_back(section.colour[t[k]]);
        out.material.push_back(section.material[t[k]]);
        out.param.push_back(glm::dvec2(0.0));
        remap[t[k]] = static_cast<unsigned>(out.position.size() - 1);
      }
      t[k] = remap[t[k]];
    }
    if (!face.outward) std::swap(t[1], t[2]);
    out.triangle.push_back(t);
  }
  return out;
}

/// `cells` with its planes moved for attempt `attempt` and put in general position against the
/// vertices of `model` (see kMaxCutAttempts).
CutCells general_position(const CutCells& cells, const DsModel& model, int attempt, double edge_m) {
  CutCells out = cells;
  const double clearance = kVertexClearance * edge_m;
  for (Plane& plane : out.planes) {
    const bool through_axis =
        std::fabs(plane.normal.y) < 1e-12 && std::fabs(glm::dot(plane.point, plane.normal)) < 1e-12;
    if (through_axis) continue;
    const glm::dvec3 base = plane.point + plane.normal * (attempt * kNudgeOffset * edge_m);
    // Steps of 2.5 clearances: a band of width 2 clearances around the plane, clear of vertices.
    for (int step = 0; step < 64; ++step) {
      plane.point = base + plane.normal * (2.5 * step * clearance);
      bool clear = true;
      for (const DsSurface& surface : model.surfaces) {
        for (auto vh : surface.mesh.vertices()) {
          const auto& p = surface.mesh.point(vh);
          const double d =
              std::fabs(glm::dot(glm::dvec3(p[0], p[1], p[2]) - plane.point, plane.normal));
          if (d > kOnPlane_m && d < clearance) {
            clear = false;
            break;
          }
        }
        if (!clear) break;
      }
      if (clear) break;
    }
  }
  return out;
}

/// Caps made at once at most, each on its own thread, when the thread count is left to us
/// (the threads of a cut of hundreds of slices take the next cap when they finish one).
constexpr size_t kCapsAtOnce = 32;

/// Whether a point of plane `plane` (a triangle's centroid) lies on a face of cell k.
bool on_face_of(const CutCells& cells, size_t k, int plane, const glm::dvec3& c) {
  const Cell& cell = cells.cells[k];
  for (const CellFace& f : cell.faces)
    if (f.plane == plane && in_cell(cells, cell, c, plane)) return true;
  return false;
}

/// Whether a point of plane `plane` lies on a face of one of `cells` (all cells when `only` is
/// null, else those it marks).
bool on_cell_face(const CutCells& cells, int plane, const glm::dvec3& c,
                  const std::vector<bool>* only) {
  for (size_t k = 0; k < cells.cells.size(); ++k)
    if ((!only || (*only)[k]) && on_face_of(cells, k, plane, c)) return true;
  return false;
}

/// The pieces of `model` in `cells` (steps 1-4 of cut_pieces); `stones`: its rigid surfaces'
/// plan, or null when it has none.
PieceSet pieces_in_cells(const DsModel& original, const CutCells& cells,
                         const DiffusionBackend& diffusion, const PieceOptions& options,
                         const StonePlan* stones) {
  // The sections and walls see each stone as hollow and what is inside it as absent.
  const DsModel& model = stones ? stones->hollowed : original;
  PieceSet set;
  set.cells = cells;
  const int threads = diffusion.threads();
  const size_t planes = cells.planes.size();

  // 1. One cross-section per plane meshed, restricted to the cells that have a face on it.
  const auto sections_start = std::chrono::steady_clock::now();
  CrossSectionOptions section_options = options.section;
  section_options.merge_boundary = false;
  std::vector<std::optional<Outcome<MeshedSection>>> meshed(planes);
  parallel_chunks(planes, 1, threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i != end; ++i) {
      CapRestriction restriction;
      for (size_t j = 0; j < planes; ++j)
        if (j != i) restriction.split_planes.push_back(cells.planes[j]);
      const int plane = static_cast<int>(i);
      restriction.keep = [&cells, plane](const glm::dvec3& c) {
        return on_cell_face(cells, plane, c, nullptr);
      };
      meshed[i] = mesh_cross_section(model, cells.planes[i], section_options, restriction);
    }
  });
  set.seconds_sections = seconds_since(sections_start);

  // 2. The skin and the walls of hollow regions, each showing its outward side, clipped to
  // every cell: a cell holds a piece when some part of them or a cap lies in it.
  const auto clip_start = std::chrono::steady_clock::now();
  struct Source {
    int surface;
    PartKind kind;
    ShadedMesh mesh;
  };
  std::vector<Source> sources;
  sources.push_back({0, PartKind::Skin, shaded_surface(model.skin(), true, false)});
  for (size_t s = 1; s < model.surfaces.size(); ++s) {
    const DsSurface& surface = model.surfaces[s];
    if (surface.role == SurfaceRole::Grain || surface.visible_front == surface.visible_back)
      continue;
    // The hollow side faces out of the piece and shows the material side's colour.
    const bool hollow_back = !surface.visible_back;
    sources.push_back(
        {static_cast<int>(s), PartKind::Wall, shaded_surface(surface, hollow_back, hollow_back)});
  }
  std::vector<bool> has_cap(cells.cells.size(), false);
  for (size_t i = 0; i < planes; ++i) {
    if (!*meshed[i]) continue;
    for (const glm::dvec3& c : (*meshed[i])->triangle_centroids())
      for (size_t k = 0; k < cells.cells.size(); ++k)
        if (!has_cap[k] && on_face_of(cells, k, static_cast<int>(i), c)) has_cap[k] = true;
  }
  // Each stone goes whole to one cell: there, its own wall is inside the piece, and its
  // surface outside the cell, showing the stone's colour, closes the piece instead.
  std::vector<int> holder;
  if (stones)
    for (const RigidStone& stone : stones->stones)
      holder.push_back(holder_cell(stone, cells, options.stone_seed));
  auto held_here = [&](int surface, size_t c) {
    if (!stones) return false;
    for (size_t k = 0; k < stones->stones.size(); ++k)
      if (stones->stones[k].surface == surface && holder[k] == static_cast<int>(c)) return true;
    return false;
  };
  std::vector<Piece> made;
  for (size_t c = 0; c < cells.cells.size(); ++c) {
    Piece piece;
    piece.cell = static_cast<int>(c);
    for (const Source& src : sources) {
      if (held_here(src.surface, c)) continue;
      ShadedMesh clipped = clip_to_cell(src.mesh, cells, cells.cells[c]);
      if (!clipped.triangle.empty()) piece.parts.push_back({src.kind, src.surface, -1, clipped});
    }
    for (size_t k = 0; stones && k < stones->stones.size(); ++k) {
      if (holder[k] != static_cast<int>(c)) continue;
      const RigidStone& stone = stones->stones[k];
      const DsSurface& surface = original.surfaces[static_cast<size_t>(stone.surface)];
      const ShadedMesh outside =
          shaded_surface(surface, !stone.front_outside, !stone.front_outside);
      for (ShadedMesh& part : outside_cell(outside, cells, cells.cells[c]))
        piece.parts.push_back({PartKind::Stone, stone.surface, -1, std::move(part)});
    }
    if (!piece.parts.empty() || has_cap[c]) made.push_back(std::move(piece));
  }
  set.pieces_cut = made.size();
  std::vector<size_t> kept(made.size());
  for (size_t k = 0; k < kept.size(); ++k) kept[k] = k;
  if (options.keep_pieces) kept = options.keep_pieces(made.size());
  std::vector<bool> kept_cell(cells.cells.size(), false);
  for (size_t k : kept) kept_cell[static_cast<size_t>(made.at(k).cell)] = true;
  set.seconds_clip = seconds_since(clip_start);

  // 3. The sections coloured where a kept piece has a cap: at once, on as many threads as the
  // user gave (kCapsAtOnce when left to us), their diffusions in shared batches, unless one
  // thread is all we have.
  const auto colour_start = std::chrono::steady_clock::now();
  std::vector<bool> kept_face(planes, false);
  for (size_t k = 0; k < cells.cells.size(); ++k)
    for (const CellFace& f : cells.cells[k].faces)
      if (kept_cell[k]) kept_face[static_cast<size_t>(f.plane)] = true;
  std::vector<size_t> to_colour;
  for (size_t i = 0; i < planes; ++i) {
    if (!*meshed[i] || !kept_face[i]) continue;
    const int plane = static_cast<int>(i);
    if (kept.size() < made.size())
      (*meshed[i])->restrict_to([&cells, &kept_cell, plane](const glm::dvec3& c) {
        return on_cell_face(cells, plane, c, &kept_cell);
      });
    to_colour.push_back(i);
  }
  std::vector<std::optional<Outcome<CrossSection>>> coloured(planes);
  auto colour_section = [&](size_t n, const DiffusionBackend& backend) {
    const size_t i = to_colour[n];
    coloured[i] = colour_cross_section(std::move(**meshed[i]), backend);
  };
  const bool at_once = to_colour.size() > 1 && threads != 1;
  if (at_once)
    set.seconds_diffuse =
        run_with_shared_batches(diffusion, to_colour.size(), colour_section,
                                threads > 0 ? static_cast<size_t>(threads) : kCapsAtOnce)
            .seconds_diffuse;
  else
    for (size_t n = 0; n < to_colour.size(); ++n) colour_section(n, diffusion);
  for (size_t i = 0; i < planes; ++i) {
    if (coloured[i] && *coloured[i]) {
      CrossSection& section = **coloured[i];
      set.diffused += section.diffused;
      if (!at_once) set.seconds_diffuse += section.seconds_diffuse;
      set.sections.push_back(std::move(section));
    } else {
      set.sections.push_back(CrossSection{});       // no cap on this plane: it misses the object,
      set.sections.back().plane = cells.planes[i];  // or no kept piece has one there
    }
  }
  set.seconds_sections += seconds_since(colour_start);

  // 4. Per kept piece: add the caps, stitch.
  const auto stitch_start = std::chrono::steady_clock::now();
  const double tolerance =
      std::max(options.stitch_tolerance * options.section.edge_m, 2 * kOnPlane_m);
  for (size_t k : kept) {
    Piece& piece = made[k];
    const Cell& cell = cells.cells[static_cast<size_t>(piece.cell)];
    for (const CellFace& face : cell.faces) {
      const CrossSection& section = set.sections[face.plane];
      ShadedMesh cap = cap_in_cell(section, cells, cell, face);
      if (!cap.triangle.empty()) piece.parts.push_back({PartKind::Cap, -1, face.plane, cap});
    }
    if (piece.parts.empty()) continue;
    std::vector<ShadedMesh*> meshes;
    for (PiecePart& part : piece.parts) meshes.push_back(&part.mesh);
    const StitchStats stats = stitch_seams(meshes, tolerance);
    set.stitched_vertices += stats.snapped + stats.inserted;
    set.pieces.push_back(std::move(piece));
  }
  set.seconds_clip += seconds_since(stitch_start);
  return set;
}

}  // namespace

Outcome<PieceSet> cut_pieces(const DsModel& model, const CutSpec& cut,
                             const DiffusionBackend& diffusion, const PieceOptions& options) {
  const CutCells cells =
      make_cut_cells(cut, model.bbox_min, model.bbox_max,
                     model.bent_axis ? &*model.bent_axis : nullptr,
                     model.cut_axis ? &*model.cut_axis : nullptr, model.knife, model.halves_across);
  // Nudging helps only where there are planes to move and the uncut skin is itself sound.
  const bool may_retry =
      !cells.planes.empty() &&
      check_manifold(shaded_surface(model.skin(), true, false), kMinVertexSeparation_m).has_value();
  const std::optional<StonePlan> stones = plan_stones(model);
  PieceSet set;
  for (int attempt = 0;; ++attempt) {
    const CutCells moved = general_position(cells, model, attempt, options.section.edge_m);
    PieceSet next = pieces_in_cells(model, moved, diffusion, options, stones ? &*stones : nullptr);
    const auto check_start = std::chrono::steady_clock::now();
    for (const Piece& piece : next.pieces)
      if (!check_manifold(merge_parts(piece), kMinVertexSeparation_m)) ++next.defective_pieces;
    next.seconds_clip += seconds_since(check_start);
    // Totals over all attempts.
    next.seconds_sections += set.seconds_sections;
    next.seconds_diffuse += set.seconds_diffuse;
    next.seconds_clip += set.seconds_clip;
    next.diffused += set.diffused;
    next.stitched_vertices += set.stitched_vertices;
    next.attempts = attempt + 1;
    set = std::move(next);
    if (set.defective_pieces == 0 || !may_retry || attempt + 1 == kMaxCutAttempts) break;
  }
  if (set.pieces.empty()) return Outcome<PieceSet>::none(kCutMisses);
  if (cut.type == CutType::Plane && set.pieces_cut < 2)
    return Outcome<PieceSet>::none(kPlaneMisses);
  return set;
}

ShadedMesh merge_parts(const Piece& piece) {
  ShadedMesh out;
  for (const PiecePart& part : piece.parts) {
    const unsigned base = static_cast<unsigned>(out.position.size());
    out.position.insert(out.position.end(), part.mesh.position.begin(), part.mesh.position.end());
    out.normal.insert(out.normal.end(), part.mesh.normal.begin(), part.mesh.normal.end());
    out.colour.insert(out.colour.end(), part.mesh.colour.begin(), part.mesh.colour.end());
    out.material.insert(out.material.end(), part.mesh.material.begin(), part.mesh.material.end());
    if (part.mesh.param.empty()) out.param.resize(out.position.size(), glm::dvec2(0.0));
    else out.param.insert(out.param.end(), part.mesh.param.begin(), part.mesh.param.end());
    for (const glm::uvec3& t : part.mesh.triangle) out.triangle.push_back(t + base);
  }
  return out;
}

std::vector<unsigned> part_vertex_offsets(const Piece& piece) {
  std::vector<unsigned> offsets{0};
  for (const PiecePart& part : piece.parts)
    offsets.push_back(offsets.back() + static_cast<unsigned>(part.mesh.position.size()));
  return offsets;
}

const PiecePart* skin_part(const Piece& piece) {
  return !piece.parts.empty() && piece.parts[0].kind == PartKind::Skin ? &piece.parts[0] : nullptr;
}

size_t surface_triangle_count(const Piece& piece) {
  size_t n = 0;
  for (const PiecePart& part : piece.parts)
    if (part.kind != PartKind::Cap) n += part.mesh.triangle.size();
  return n;
}

}  // namespace cutaway
