// Settling benchmark (issue: full scenes fast; settling close to linear in the piece count):
// the market stall's mix of cut pieces (scenes/market.yaml: tomato wedges, cucumber and kiwi
// slices, ...) laid out and settled on its 90 x 60 cm board, 40 to 500 pieces, as the scene
// builder does it (height-field layout, then Bullet). The pieces come from a pool of a few
// objects per item, cut once (vertex colours, a coarse cube: their colours do not matter
// here), and are used again in turn, so the line per count measures layout and physics only.
//
// Run:   make bench
//   or:  cmake --build build --target bench_settle && ./build/bench_settle [--counts 40,80,...]
//        [--scene FILE] (that scene's items and container instead of the market's)
//        [--freeze S] (SettleOptions::freeze_after_s; 0: no piece is frozen, as before)
// One line per count: pieces placed and lost, drops again, simulated seconds and steps, the
// work of the settling (bodies simulated per step, summed: frozen pieces are not), the
// stability check, wall seconds of the layout and of the settling, and seconds per piece.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "base/random.h"
#include "base/timer.h"
#include "cut/object_cut.h"
#include "io/scene_parser.h"
#include "placement/collision_shape.h"
#include "placement/physics_settle.h"
#include "placement/scene_layout.h"
#include "scene/scene_builder.h"

namespace {

using Clock = std::chrono::steady_clock;
using cutaway::seconds_since;

/// One cut piece of the pool: its mesh as cut, what the layout needs and its rigid body.
struct PoolPiece {
  cutaway::ShadedMesh shape;
  cutaway::LayoutPiece layout;  // mesh set when laid out
  cutaway::CollisionShape collision;
  double density_kg_m3 = 1000;
};

/// `per_item` objects of each item of `scene`, cut as the scene asks.
std::vector<PoolPiece> cut_pool(const cutaway::Scene& scene, int per_item) {
  std::vector<PoolPiece> pool;
  cutaway::SceneAssets assets;
  cutaway::ObjectCutStats stats;
  for (size_t i = 0; i < scene.items.size(); ++i) {
    const cutaway::SceneItem& item = scene.items[i];
    const cutaway::PieceMaterials materials = cutaway::add_piece_materials(
        assets, item.tmpl->name, item.tmpl->skin_material, item.tmpl->cut_material);
    for (int j = 0; j < std::min(per_item, item.count); ++j) {
      const uint64_t seed = cutaway::object_seed(scene.seed, static_cast<int>(i), j, 1);
      const cutaway::Variant variant = cutaway::make_variant(*item.tmpl, seed);
      cutaway::ObjectCutOptions o;
      o.cut = item.cut;
      o.cap_colours = cutaway::CapColours::Vertex;
      const auto diffusion = cutaway::make_cpu_diffusion(variant.model, {4, 0});
      cutaway::CutObject made =
          *cutaway::cut_object(assets, variant, seed, materials, "pool", *diffusion, o, stats);
      for (size_t q = 0; q < made.set.pieces.size(); ++q) {
        const cutaway::Piece& piece = made.set.pieces[q];
        PoolPiece p;
        p.shape = std::move(made.shapes[q]);
        p.layout = {nullptr,      cutaway::largest_cap_normal(piece),
                    item.arrange, static_cast<int>(pool.size()),
                    piece.cell,   cutaway::cut_faces(piece)};
        p.collision = cutaway::collision_shape(p.shape);
        p.density_kg_m3 = item.tmpl->density_kg_m3;
        pool.push_back(std::move(p));
      }
    }
  }
  return pool;
}

std::vector<int> parse_counts(const char* text) {
  std::vector<int> counts;
  for (const char* at = text; *at;) {
    counts.push_back(std::atoi(at));
    at = std::strchr(at, ',');
    if (!at) break;
    ++at;
  }
  return counts;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> counts = {40, 80, 160, 320, 500};
  std::string file = std::string(CUTAWAY_SOURCE_DIR) + "/scenes/market.yaml";
  cutaway::SettleOptions settle;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (std::strcmp(argv[a], "--counts") == 0) counts = parse_counts(argv[a + 1]);
    if (std::strcmp(argv[a], "--scene") == 0) file = argv[a + 1];
    if (std::strcmp(argv[a], "--freeze") == 0) settle.freeze_after_s = std::atof(argv[a + 1]);
  }
  const cutaway::Scene scene = cutaway::load_scene(file);
  const auto t_pool = Clock::now();
  const std::vector<PoolPiece> pool = cut_pool(scene, 2);
  std::printf("settle: a pool of %zu pieces of %s cut in %.1f s\n", pool.size(), scene.name.c_str(),
              seconds_since(t_pool));
  for (const int n : counts) {
    // Pieces of the pool in turn, in the seeded order the scene builder mixes them in.
    std::vector<size_t> which = cutaway::placement_order(static_cast<size_t>(n), scene.seed);
    for (size_t& k : which) k %= pool.size();
    std::vector<cutaway::LayoutPiece> layout;
    for (size_t k = 0; k < which.size(); ++k) {
      layout.push_back(pool[which[k]].layout);
      layout.back().mesh = &pool[which[k]].shape;
      layout.back().group = static_cast<int>(k);  // a fan row per use of a piece
    }
    const auto t_layout = Clock::now();
    cutaway::LayoutOptions layout_options;
    layout_options.to_camera =
        cutaway::layout_view(scene.container, cutaway::scene_view_direction(scene)).to_camera;
    const std::vector<cutaway::Placement> drops = cutaway::layout_pieces(
        layout, scene.container, layout_options, cutaway::derive_seed(scene.seed, {~0ull, 4}));
    const double layout_s = seconds_since(t_layout);
    std::vector<cutaway::SettleBody> bodies(which.size());
    int dropped = 0;
    for (size_t k = 0; k < which.size(); ++k) {
      bodies[k] = {&pool[which[k]].collision, pool[which[k]].density_kg_m3, drops[k]};
      dropped += drops[k].placed;
    }
    const auto t_settle = Clock::now();
    const cutaway::SettleResult r = cutaway::settle_pieces(bodies, scene.container, settle);
    const double settle_s = seconds_since(t_settle);
    const long placed = std::count_if(r.placements.begin(), r.placements.end(),
                                      [](const cutaway::Placement& p) { return p.placed; });
    std::printf("settle %3d pieces: %3ld placed (%d laid out, %d lost, %d drops again), "
                "%.2f s simulated in %d steps, %lld body steps, stability %.2f mm (check %d of "
                "%d)%s; layout %.2f s, settling %.1f s (%.3f s per piece)\n",
                n, placed, dropped, r.lost, r.redrops, r.simulated_s, r.steps, r.body_steps,
                1000 * r.stability_motion_m, r.kept_round, r.verify_rounds,
                r.stable ? "" : " (over 1 mm)", layout_s, settle_s, settle_s / n);
    std::fflush(stdout);
  }
  return 0;
}
