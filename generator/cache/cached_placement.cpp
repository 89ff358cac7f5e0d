#include "cache/cached_placement.h"

#include <nlohmann/json.hpp>

#include "base/error.h"
#include "base/hash.h"
#include "base/source_fingerprint.h"

namespace cutaway {

namespace {

/// The version of the payload's layout (and of the key's), part of every key.
constexpr int kPayloadVersion = 2;

// A field added to one of these structs must be added to the key below: their sizes remind.
static_assert(sizeof(Container) == 64, "a new Container field: add it to placement_cache_key");
static_assert(sizeof(LayoutOptions) == 120,
              "a new LayoutOptions field: add it to placement_cache_key");
static_assert(sizeof(SettleOptions) == 216,
              "a new SettleOptions field: add it to placement_cache_key");

nlohmann::ordered_json vec_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::ordered_json container_json(const Container& c) {
  return {{"type", static_cast<int>(c.type)},
          {"diameter_m", c.diameter_m},
          {"width_m", c.width_m},
          {"depth_m", c.depth_m},
          {"height_m", c.height_m},
          {"colour", vec_json(c.colour)}};
}

nlohmann::ordered_json layout_json(const LayoutOptions& o) {
  return {{"cell_m", o.cell_m},
          {"candidates", o.candidates},
          {"clearance_m", o.clearance_m},
          {"centre_weight", o.centre_weight},
          {"heap_centre_weight", o.heap_centre_weight},
          {"to_camera", vec_json(o.to_camera)},
          {"none_radius_m", o.none_radius_m},
          {"tilt_deg", o.tilt_deg},
          {"fan_tilt_deg", o.fan_tilt_deg},
          {"fan_step", o.fan_step},
          {"fan_headings", o.fan_headings},
          {"fan_min_row", o.fan_min_row},
          {"scatter_gap_m", o.scatter_gap_m},
          {"scan_step_m", o.scan_step_m}};
}

nlohmann::ordered_json settle_json(const SettleOptions& o) {
  return {{"time_step_s", o.time_step_s},
          {"max_seconds", o.max_seconds},
          {"margin_m", o.margin_m},
          {"solver_iterations", o.solver_iterations},
          {"check_solver_iterations", o.check_solver_iterations},
          {"verify_seconds", o.verify_seconds},
          {"stable_motion_m", o.stable_motion_m},
          {"check_motion_m", o.check_motion_m},
          {"max_verify_rounds", o.max_verify_rounds},
          {"resettle_gap_m", o.resettle_gap_m},
          {"friction", o.friction},
          {"rolling_friction_m", o.rolling_friction_m},
          {"linear_damping", o.linear_damping},
          {"angular_damping", o.angular_damping},
          {"sleep_speed_m_s", o.sleep_speed_m_s},
          {"sleep_spin_rad_s", o.sleep_spin_rad_s},
          {"rest_motion_m", o.rest_motion_m},
          {"freeze_after_s", o.freeze_after_s},
          {"free_seconds", o.free_seconds},
          {"container_segments", o.container_segments},
          {"container_profile_samples", o.container_profile_samples},
          {"max_redrops", o.max_redrops},
          {"max_overhang", o.max_overhang},
          {"min_cut_face_up", o.min_cut_face_up},
          {"to_camera", vec_json(o.to_camera)},
          {"min_cut_face_seen", o.min_cut_face_seen},
          {"none_radius_m", o.none_radius_m}};
}

}  // namespace

std::string placement_cache_key(const PlacementKeyInputs& in) {
  if (!in.container || !in.layout || !in.settle)
    throw InternalError("placement_cache_key: missing inputs");
  nlohmann::ordered_json cuts = nlohmann::ordered_json::array();
  for (const std::string& key : in.cut_keys) cuts.push_back(hex64(fnv1a64(key)));
  nlohmann::ordered_json arrange = nlohmann::ordered_json::array();
  for (Arrangement a : in.arrange) arrange.push_back(static_cast<int>(a));
  const nlohmann::ordered_json key = {{"cutaway", CUTAWAY_VERSION},
                                      {"sources", source_fingerprint()},
                                      {"placements", kPayloadVersion},
                                      {"cuts", cuts},
                                      {"arrange", arrange},
                                      {"seed", in.seed},
                                      {"container", container_json(*in.container)},
                                      {"layout", layout_json(*in.layout)},
                                      {"settle", settle_json(*in.settle)}};
  return key.dump();
}

}  // namespace cutaway
