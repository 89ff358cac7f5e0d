#include "placement/physics_settle.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <limits>
#include <optional>

#include <btBulletDynamicsCommon.h>
#include <glm/common.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "base/error.h"
#include "base/finite.h"
#include "placement/container_mesh.h"
#include "placement/hull_shape.h"
#include "placement/ordered_dispatcher.h"

namespace cutaway {

namespace {

/// Bullet works best with bodies of about one unit: the simulation runs in centimetres.
constexpr double kUnitsPerMetre = 100;

btVector3 to_bt(const glm::dvec3& p) {
  return btVector3(static_cast<btScalar>(p.x * kUnitsPerMetre),
                   static_cast<btScalar>(p.y * kUnitsPerMetre),
                   static_cast<btScalar>(p.z * kUnitsPerMetre));
}

glm::dvec3 from_bt(const btVector3& v) { return glm::dvec3(v.x(), v.y(), v.z()) / kUnitsPerMetre; }

/// The centre of mass of body `b` placed at the object-frame pose `pose` (metres).
glm::dvec3 centre_of_mass(const SettleBody& b, const Placement& pose) {
  return pose.translation + pose.rotation * b.shape->centroid;
}

/// Steps between two looks at whether the bodies rest: a quarter second.
int steps_per_rest_check(const SettleOptions& o) {
  return std::max(1, static_cast<int>(std::lround(0.25 / o.time_step_s)));
}

/// A Bullet world holding the table, the container and the bodies, in input order.
class World {
 public:
  World(const Container& container, const SettleOptions& o) : container_(container), options_(o) {
    world_ = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher_, &broadphase_, &solver_,
                                                       &configuration_);
    world_->setGravity(btVector3(0, static_cast<btScalar>(-9.81 * kUnitsPerMetre), 0));
    world_->getSolverInfo().m_numIterations = o.solver_iterations;
    // Two friction directions per contact, kept from step to step: with one, resting pieces
    // crept 0.3-1 mm every quarter second and a bowl of nine never came to rest.
    world_->getSolverInfo().m_solverMode |=
        SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    // The table the container stands on (and that catches pieces falling out of it).
    add_static(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0), btVector3(0, 0, 0));
    if (container.type == ContainerType::Board) {
      const glm::dvec3 half(0.5 * container.width_m, 0.5 * container.height_m,
                            0.5 * container.depth_m);
      add_static(std::make_unique<btBoxShape>(to_bt(half)), to_bt({0, half.y, 0}));
    } else if (auto mesh =
                   container_mesh(container, o.container_segments, o.container_profile_samples)) {
      // The bowl and plate as a compound of convex tiles: each triangle of a coarse mesh of the
      // container, thickened 3 mm into the solid. (Against a triangle mesh, even with Bullet's
      // internal-edge correction, a tomato half on the bowl's floor never came to rest: it
      // moved 1-3 mm every quarter second for 8 s; on tiles it rests after 1 s.)
      auto compound = std::make_unique<btCompoundShape>();
      btTransform identity;
      identity.setIdentity();
      for (const glm::uvec3& t : mesh->triangle) {
        const glm::dvec3 a = mesh->position[t[0]], b = mesh->position[t[1]],
                         c = mesh->position[t[2]];
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        if (glm::length(cross) == 0) continue;
        const glm::dvec3 n = glm::normalize(cross), m = (a + b + c) / 3.0;
        // Only the surfaces pieces can rest on: the inside (facing the axis) and the rim (up).
        if (!(n.y > 0.05 || n.x * m.x + n.z * m.z < 0)) continue;
        auto tile = std::make_unique<btConvexHullShape>();
        for (const glm::dvec3& p : {a, b, c}) {
          tile->addPoint(to_bt(p), false);
          tile->addPoint(to_bt(p - 0.003 * n), false);
        }
        tile->recalcLocalAabb();
        tile->initializePolyhedralFeatures();
        tile->setMargin(static_cast<btScalar>(o.margin_m * kUnitsPerMetre));
        compound->addChildShape(identity, tile.get());
        children_.push_back(std::move(tile));
      }
      add_static(std::move(compound), btVector3(0, 0, 0));
    }
  }

  ~World() {
    for (int i = world_->getNumCollisionObjects() - 1; i >= 0; --i) {
      btCollisionObject* obj = world_->getCollisionObjectArray()[i];
      world_->removeCollisionObject(obj);
    }
  }

  /// Adds a body at `pose` (object frame placed by it), at rest; returns its index.
  size_t add_body(const SettleBody& b, const Placement& pose) {
    const CollisionShape& s = *b.shape;
    const btScalar margin = static_cast<btScalar>(options_.margin_m * kUnitsPerMetre);
    std::unique_ptr<btCollisionShape> shape;
    auto hull_of = [&](const ConvexPart& part) {
      std::vector<btVector3> corners;
      corners.reserve(part.corners.size());
      for (const glm::dvec3& p : part.corners) corners.push_back(to_bt(p - s.centroid));
      auto hull = std::make_unique<HullShape>(corners);
      // Polyhedral contact clipping: a resting face touches with all its contact points in one
      // step, where GJK finds one point a step. Without it a settled salad simulated again
      // from rest sagged 5-12 mm while its contacts were found again.
      hull->initializePolyhedralFeatures();
      hull->setMargin(std::max(margin, static_cast<btScalar>(part.outside_m * kUnitsPerMetre)));
      return hull;
    };
    if (s.parts.size() == 1) {
      shape = hull_of(s.parts[0]);
    } else {
      auto compound = std::make_unique<btCompoundShape>();
      btTransform identity;
      identity.setIdentity();
      for (const auto& part : s.parts) {
        children_.push_back(hull_of(part));
        compound->addChildShape(identity, children_.back().get());
      }
      shape = std::move(compound);
    }
    const btScalar mass = static_cast<btScalar>(b.density_kg_m3 * s.volume_m3);
    btVector3 inertia(0, 0, 0);
    shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), inertia);
    info.m_friction = static_cast<btScalar>(options_.friction);
    info.m_restitution = 0;
    // Rolling and spinning resistance: a torque up to rolling_friction_m x the normal force.
    info.m_rollingFriction = info.m_spinningFriction =
        static_cast<btScalar>(options_.rolling_friction_m * kUnitsPerMetre);
    info.m_linearDamping = static_cast<btScalar>(options_.linear_damping);
    info.m_angularDamping = static_cast<btScalar>(options_.angular_damping);
    info.m_linearSleepingThreshold =
        static_cast<btScalar>(options_.sleep_speed_m_s * kUnitsPerMetre);
    info.m_angularSleepingThreshold = static_cast<btScalar>(options_.sleep_spin_rad_s);
    auto body = std::make_unique<btRigidBody>(info);
    // Friction anchors: a contact point that sticks keeps its place on both bodies instead of
    // being found again every step.
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
    body->setWorldTransform(transform(b, pose));
    shapes_.push_back(std::move(shape));
    world_->addRigidBody(body.get());
    bodies_.push_back(std::move(body));
    mass_.push_back({mass, inertia});
    frozen_.push_back(false);
    pinned_.push_back(false);
    return bodies_.size() - 1;
  }

  /// Makes body k static where it is: it no longer moves, costs no solver work, and the
  /// bodies on it rest on it as on the container.
  void freeze(size_t k) {
    if (frozen_[k]) return;
    btRigidBody& body = *bodies_[k];
    world_->removeRigidBody(&body);
    body.setLinearVelocity(btVector3(0, 0, 0));
    body.setAngularVelocity(btVector3(0, 0, 0));
    body.setMassProps(0, btVector3(0, 0, 0));
    body.setCollisionFlags(body.getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
    world_->addRigidBody(&body);
    frozen_[k] = true;
  }

  bool frozen(size_t k) const { return frozen_[k]; }
  /// Whether any body in the world is frozen.
  bool any_frozen() const {
    for (size_t k = 0; k < bodies_.size(); ++k)
      if (frozen_[k] && bodies_[k]->isInWorld()) return true;
    return false;
  }

  /// Makes every frozen body dynamic again, at rest where it lies (pinned ones stay frozen).
  void thaw_all() {
    for (size_t k = 0; k < bodies_.size(); ++k)
      if (frozen_[k] && !pinned_[k] && bodies_[k]->isInWorld()) thaw(k);
  }

  /// Freezes body k for the rest of this world's life: thaw_all leaves it static.
  void pin(size_t k) {
    freeze(k);
    pinned_[k] = true;
  }

  /// The corners (low, high) of body k's bounding box in the world, its collision margin
  /// included (metres).
  std::pair<glm::dvec3, glm::dvec3> bounds(size_t k) const {
    btVector3 lo, hi;
    bodies_[k]->getAabb(lo, hi);
    return {from_bt(lo), from_bt(hi)};
  }

  /// The bodies in the world that are not frozen.
  size_t moving() const {
    size_t n = 0;
    for (size_t k = 0; k < bodies_.size(); ++k) n += bodies_[k]->isInWorld() && !frozen_[k];
    return n;
  }

  /// The Bullet transform of the body's centre of mass for an object-frame pose.
  static btTransform transform(const SettleBody& b, const Placement& pose) {
    const glm::dquat& q = pose.rotation;
    return btTransform(btQuaternion(static_cast<btScalar>(q.x), static_cast<btScalar>(q.y),
                                    static_cast<btScalar>(q.z), static_cast<btScalar>(q.w)),
                       to_bt(centre_of_mass(b, pose)));
  }

  /// The object-frame pose of body k.
  Placement pose(size_t k, const SettleBody& b) const {
    const btTransform& t = bodies_[k]->getWorldTransform();
    const btQuaternion r = t.getRotation();
    Placement p;
    p.placed = true;
    p.rotation = glm::normalize(glm::dquat(r.w(), r.x(), r.y(), r.z()));
    p.translation = from_bt(t.getOrigin()) - p.rotation * b.shape->centroid;
    return p;
  }

  /// Places body k at `pose`, at rest, awake (and no longer frozen).
  void reset(size_t k, const SettleBody& b, const Placement& pose) {
    if (frozen_[k]) thaw(k);
    btRigidBody& body = *bodies_[k];
    body.setWorldTransform(transform(b, pose));
    body.setLinearVelocity(btVector3(0, 0, 0));
    body.setAngularVelocity(btVector3(0, 0, 0));
    body.activate(true);
    world_->updateSingleAabb(&body);
  }

  const Container& container() const { return container_; }

  void remove(size_t k) { world_->removeRigidBody(bodies_[k].get()); }

  /// The bounding boxes (low, high corners, metres) of the bodies in the world other than the
  /// body with index `skip`.
  std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes_except(size_t skip) const {
    std::vector<std::pair<glm::dvec3, glm::dvec3>> out;
    for (size_t j = 0; j < bodies_.size(); ++j) {
      if (j == skip || !bodies_[j]->isInWorld()) continue;
      btVector3 lo, hi;
      bodies_[j]->getAabb(lo, hi);
      out.push_back({glm::dvec3(lo.x(), lo.y(), lo.z()) / kUnitsPerMetre,
                     glm::dvec3(hi.x(), hi.y(), hi.z()) / kUnitsPerMetre});
    }
    return out;
  }

  /// The highest point of any body in the world (metres).
  double top() const {
    double y = 0;
    for (const auto& b : bodies_) {
      if (!b->isInWorld()) continue;
      btVector3 lo, hi;
      b->getAabb(lo, hi);
      y = std::max(y, static_cast<double>(hi.y()) / kUnitsPerMetre);
    }
    return y;
  }

  /// The object-frame poses of the bodies (index id[k] of body k; SIZE_MAX: not placed).
  std::vector<Placement> poses(const std::vector<SettleBody>& b,
                               const std::vector<size_t>& id) const {
    std::vector<Placement> out(b.size());
    for (size_t k = 0; k < b.size(); ++k) {
      if (id[k] != SIZE_MAX && bodies_[id[k]]->isInWorld()) out[k] = pose(id[k], b[k]);
    }
    return out;
  }

  bool asleep() const {
    for (const auto& b : bodies_) {
      if (b->isInWorld() && b->getActivationState() != ISLAND_SLEEPING) return false;
    }
    return true;
  }

  void step() {
    const btScalar dt = static_cast<btScalar>(options_.time_step_s);
    world_->stepSimulation(dt, 1, dt);
  }

 private:
  btRigidBody* add_static(std::unique_ptr<btCollisionShape> shape, const btVector3& origin) {
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape.get());
    info.m_friction = static_cast<btScalar>(options_.friction);
    info.m_startWorldTransform.setOrigin(origin);
    auto body = std::make_unique<btRigidBody>(info);
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
    world_->addRigidBody(body.get());
    shapes_.push_back(std::move(shape));
    statics_.push_back(std::move(body));
    return statics_.back().get();
  }

  Container container_;
  SettleOptions options_;
  btDefaultCollisionConfiguration configuration_;
  OrderedDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_, children_;
  std::vector<std::unique_ptr<btRigidBody>> statics_, bodies_;
  /// Makes frozen body k dynamic again, with its mass and inertia, awake.
  void thaw(size_t k) {
    btRigidBody& body = *bodies_[k];
    world_->removeRigidBody(&body);
    body.setCollisionFlags(body.getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT);
    body.setMassProps(mass_[k].first, mass_[k].second);
    world_->addRigidBody(&body);
    body.activate(true);
    frozen_[k] = false;
  }

  std::vector<std::pair<btScalar, btVector3>> mass_;  // per body: its mass and inertia
  std::vector<bool> frozen_;                          // per body: made static (freeze)
  std::vector<bool> pinned_;                          // per body: frozen for good (pin)
};

/// Calls f(p) for every corner p of the body's collision shape placed at `pose` (world frame,
/// metres), part by part.
template <class F>
void for_each_corner(const SettleBody& body, const Placement& pose, F&& f) {
  for (const ConvexPart& part : body.shape->parts)
    for (const glm::dvec3& corner : part.corners) f(pose.translation + pose.rotation * corner);
}

/// How far the farthest corner of the body's collision shape lies between poses a and b (metres);
/// 0 unless placed in both.
double body_motion(const SettleBody& body, const Placement& a, const Placement& b) {
  double moved = 0;
  if (!a.placed || !b.placed) return moved;
  for (const ConvexPart& part : body.shape->parts) {
    for (const glm::dvec3& p : part.corners) {
      moved = std::max(
          moved, glm::length((a.translation + a.rotation * p) - (b.translation + b.rotation * p)));
    }
  }
  return moved;
}

/// The largest body_motion of any body between poses a and b (metres).
double largest_motion(const std::vector<SettleBody>& bodies, const std::vector<Placement>& a,
                      const std::vector<Placement>& b) {
  double moved = 0;
  for (size_t k = 0; k < bodies.size(); ++k)
    moved = std::max(moved, body_motion(bodies[k], a[k], b[k]));
  return moved;
}

/// Whether some corner of a piece's collision shape at `pose` lies more than max_overhang of
/// its size beyond the resting area's edge.
bool hangs_over(const Container& container, const SettleBody& body, const Placement& pose,
                const SettleOptions& options) {
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high = -low;
  double overhang = 0;
  for_each_corner(body, pose, [&](const glm::dvec3& p) {
    low = glm::min(low, p);
    high = glm::max(high, p);
    overhang = std::max(overhang, resting_overhang(container, p.x, p.z, options.none_radius_m));
  });
  const glm::dvec3 extent = high - low;
  return overhang > options.max_overhang * std::max({extent.x, extent.y, extent.z});
}

/// Whether a piece at `pose` lies in the container: its centre of mass over the resting area,
/// above the table and below `ceiling` (higher, a failed simulation step has thrown it), and
/// not hanging over the resting area's edge (hangs_over).
bool rests_inside(const Container& container, const SettleBody& body, const Placement& pose,
                  double ceiling, const SettleOptions& options) {
  const glm::dvec3 c = centre_of_mass(body, pose);
  if (!all_finite(c) || c.y <= 0 || c.y >= ceiling ||
      !rest_height(container, c.x, c.z, options.none_radius_m).has_value())
    return false;
  return !hangs_over(container, body, pose, options);
}

/// Whether a piece at `pose` shows its cut face: none to show, or its normal's upward
/// component at least min_cut_face_up and, with a camera, its component towards the camera
/// at least min_cut_face_seen.
bool shows_cut_face(const SettleBody& body, const Placement& pose, const SettleOptions& options) {
  if (glm::length(body.cut_face) == 0) return true;
  const glm::dvec3 n = pose.rotation * glm::normalize(body.cut_face);
  if (n.y < options.min_cut_face_up) return false;
  return glm::length(options.to_camera) == 0 ||
         glm::dot(n, glm::normalize(options.to_camera)) >= options.min_cut_face_seen;
}

/// Spots tried across the resting area, a side, by over_free_ground.
constexpr int kFreeGroundSteps = 24;

/// `pose` (a piece as it rests) moved level, its turn kept, so that its centre of mass lies
/// over the freest spot: where the box of its collision shape's corners overlaps the other
/// bodies' boxes least in plan (the sum of the overlaps' areas), the nearest to `target` (x,
/// z, metres) among equals, and does not hang over the resting area's edge (hangs_over). The
/// spots: `target` and a kFreeGroundSteps square grid over the resting area (rest_radius),
/// those whose centre lies over it (rest_height). None when every spot hangs over.
std::optional<Placement> over_free_ground(const World& world, const SettleBody& body, size_t self,
                                          const Placement& pose, const glm::dvec2& target,
                                          const SettleOptions& options) {
  const glm::dvec3 centre = centre_of_mass(body, pose);
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi = -lo;  // footprint about centre
  for_each_corner(body, pose, [&](const glm::dvec3& p) {
    const glm::dvec2 plan(p.x - centre.x, p.z - centre.z);
    lo = glm::min(lo, plan);
    hi = glm::max(hi, plan);
  });
  const auto others = world.boxes_except(self);
  const double r = rest_radius(world.container(), options.none_radius_m);
  std::vector<glm::dvec2> spots{target};
  for (int i = 0; i <= kFreeGroundSteps; ++i)
    for (int j = 0; j <= kFreeGroundSteps; ++j)
      spots.push_back(
          glm::dvec2(-r + 2 * r * i / kFreeGroundSteps, -r + 2 * r * j / kFreeGroundSteps));
  std::optional<Placement> best;
  double best_overlap = std::numeric_limits<double>::infinity(), best_distance = best_overlap;
  for (const glm::dvec2& spot : spots) {
    if (!rest_height(world.container(), spot.x, spot.y, options.none_radius_m)) continue;
    double overlap = 0;
    for (const auto& [olo, ohi] : others) {
      const double dx = std::min(ohi.x, spot.x + hi.x) - std::max(olo.x, spot.x + lo.x);
      const double dz = std::min(ohi.z, spot.y + hi.y) - std::max(olo.z, spot.y + lo.y);
      if (dx > 0 && dz > 0) overlap += dx * dz;
    }
    const double distance = glm::length(spot - target);
    if (overlap > best_overlap || (overlap == best_overlap && distance >= best_distance)) continue;
    Placement moved = pose;
    moved.translation += glm::dvec3(spot.x - centre.x, 0, spot.y - centre.z);
    if (hangs_over(world.container(), body, moved, options)) continue;
    best = moved;
    best_overlap = overlap;
    best_distance = distance;
  }
  return best;
}

/// The turn about the vertical (+Y) that brings the horizontal part of `face` to that of
/// `to_camera`; none where either has no horizontal part.
glm::dquat spin_towards(const glm::dvec3& face, const glm::dvec3& to_camera) {
  const glm::dvec2 a(face.x, face.z), b(to_camera.x, to_camera.z);
  if (glm::length(a) < 1e-9 || glm::length(b) < 1e-9) return glm::dquat(1, 0, 0, 0);
  // Rotating by t about +Y takes (x, z) to (x cos t + z sin t, -x sin t + z cos t).
  const double t = std::atan2(a.y * b.x - a.x * b.y, a.x * b.x + a.y * b.y);
  return glm::angleAxis(t, glm::dvec3(0, 1, 0));
}

/// Steps `world` until it rests (no corner moved more than rest_motion_m in a quarter second,
/// every body sleeps, or every body is frozen) or max_seconds pass; a body that rests for
/// freeze_after_s meanwhile is frozen (World::freeze). Pieces that left the container (or hang
/// over its edge, rests_inside) are then dropped again from above the pile and the world runs
/// on: one that rests over the container but hangs over its edge as it lies, moved to the
/// freest ground where it does not (over_free_ground); else from its drop pose, nearer the
/// axis each time. After max_redrops a piece is removed and counted lost (its id becomes
/// SIZE_MAX). A piece lying on its cut face (shows_cut_face) is dropped again too, from its
/// drop pose turned with that face straight up, and one whose face is up but turned away from
/// the camera from where it lay, spun about the vertical until the face leans towards the
/// camera (spin_towards); either is kept as it lies after max_redrops. Adds to r.steps,
/// r.body_steps, r.redrops and r.lost; sets r.all_asleep.
void run_to_rest(World& world, const std::vector<SettleBody>& bodies, std::vector<size_t>& id,
                 std::vector<int>& drops, double ceiling, const SettleOptions& options,
                 SettleResult& r) {
  const int max_steps = static_cast<int>(std::ceil(options.max_seconds / options.time_step_s));
  const int check_every = steps_per_rest_check(options);
  // A body that has rested for still_checks looks in a row is frozen.
  const double look_s = check_every * options.time_step_s;
  const int still_checks =
      std::max(1, static_cast<int>(std::lround(options.freeze_after_s / look_s)));
  std::vector<int> still(bodies.size(), 0);
  for (;;) {
    int steps = 0;
    bool at_rest = false;
    std::vector<Placement> before = world.poses(bodies, id);
    for (; steps < max_steps && !at_rest; ++steps) {
      r.body_steps += world.moving();
      world.step();
      if ((steps + 1) % check_every != 0) continue;
      std::vector<Placement> now = world.poses(bodies, id);
      double moved = 0;
      for (size_t k = 0; k < bodies.size(); ++k) {
        if (id[k] == SIZE_MAX || world.frozen(id[k])) continue;
        const double m = body_motion(bodies[k], before[k], now[k]);
        moved = std::max(moved, m);
        still[k] = m < options.rest_motion_m ? still[k] + 1 : 0;
        if (options.freeze_after_s > 0 && still[k] >= still_checks) world.freeze(id[k]);
      }
      at_rest = world.asleep() || world.moving() == 0 || moved < options.rest_motion_m;
      before = std::move(now);
    }
    r.steps += steps;
    r.all_asleep = at_rest;
    // Pieces that left the container are dropped again from above the pile.
    bool dropped = false;
    const double top = world.top();
    for (size_t k = 0; k < bodies.size(); ++k) {
      if (id[k] == SIZE_MAX) continue;
      const Placement pose = world.pose(id[k], bodies[k]);
      const bool inside = rests_inside(world.container(), bodies[k], pose, ceiling, options);
      if (inside && (shows_cut_face(bodies[k], pose, options) || drops[k] == options.max_redrops))
        continue;
      if (drops[k] == options.max_redrops) {
        world.remove(id[k]);
        id[k] = SIZE_MAX;
        ++r.lost;
        continue;
      }
      ++drops[k];
      ++r.redrops;
      Placement again = bodies[k].drop;
      const glm::dvec3 was = centre_of_mass(bodies[k], pose);
      const glm::dvec3 face = inside ? pose.rotation * glm::normalize(bodies[k].cut_face)
                                     : glm::dvec3(0.0);  // inside here: it has a cut face
      std::optional<Placement> moved;
      if (inside && face.y >= options.min_cut_face_up) {
        // Face up but turned away from the camera: the way it rests suits it (a thick half
        // leans back on its round side however it is dropped), so it is spun about the
        // vertical through its centre of mass, where it lay, until its face leans towards the
        // camera. (Dropped again from its drop pose, it came to lean back again or fell onto a
        // neighbour and hid it.)
        again.rotation = spin_towards(face, options.to_camera) * pose.rotation;
        again.translation = pose.translation + was - centre_of_mass(bodies[k], again);
      } else if (!inside && all_finite(was) && was.y > 0 && was.y < ceiling &&
                 rest_height(world.container(), was.x, was.z, options.none_radius_m) &&
                 (moved = over_free_ground(world, bodies[k], id[k], pose, glm::dvec2(was.x, was.z),
                                           options))) {
        // It rests over the container but hangs over its edge: moved as it lies to the
        // nearest free ground where it does not (dropped again from its drop pose, nearer the
        // middle, a large half fell onto a neighbour and hid it).
        again = *moved;
      } else {
        if (inside)  // it lay on its cut face: dropped again with the face straight up
          again.rotation =
              glm::rotation(glm::normalize(again.rotation * glm::normalize(bodies[k].cut_face)),
                            glm::dvec3(0, 1, 0)) *
              again.rotation;
        // Each drop again nearer the container's axis (a quarter of the way per drop): a piece
        // that left the container from its drop pose near an edge would leave it again there.
        const double pull = static_cast<double>(drops[k]) / (options.max_redrops + 1);
        const glm::dvec3 drop_centre = centre_of_mass(bodies[k], again);
        again.translation -= pull * glm::dvec3(drop_centre.x, 0, drop_centre.z);
      }
      double low = 0;  // the lowest corner below the piece's origin
      for_each_corner(bodies[k], Placement{true, again.rotation, glm::dvec3(0.0)},
                      [&](const glm::dvec3& p) { low = std::min(low, p.y); });
      again.translation.y = top + 0.005 - low;
      world.reset(id[k], bodies[k], again);
      still[k] = 0;
      dropped = true;
    }
    if (!dropped) break;
  }
}

/// run_to_rest, and then, where pieces were frozen, every piece free again from where it lies
/// until the layout rests or free_seconds pass: a piece frozen before others came to
/// lie on it settles under their weight, as it will in the stability check. r.all_asleep stays
/// the verdict of the first run (the second is bounded by design).
void settle_world(World& world, const std::vector<SettleBody>& bodies, std::vector<size_t>& id,
                  std::vector<int>& drops, double ceiling, const SettleOptions& options,
                  SettleResult& r) {
  run_to_rest(world, bodies, id, drops, ceiling, options, r);
  if (options.freeze_after_s <= 0 || !world.any_frozen()) return;
  const bool rested = r.all_asleep;
  world.thaw_all();
  SettleOptions free = options;
  free.freeze_after_s = 0;
  free.max_seconds = std::min(options.max_seconds, options.free_seconds);
  run_to_rest(world, bodies, id, drops, ceiling, free, r);
  r.all_asleep = rested;
}

/// After a failed stability check in `world`, which started from `checked`: pins (World::pin)
/// every body that moved at most options.check_motion_m since, unless its bounds come within
/// options.resettle_gap_m of those of a body that moved more. The settling that follows then
/// moves only where the check found motion.
void pin_resting(World& world, const std::vector<SettleBody>& bodies, const std::vector<size_t>& id,
                 const std::vector<Placement>& checked, const SettleOptions& options) {
  const std::vector<Placement> now = world.poses(bodies, id);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> moved;  // their bounds
  std::vector<bool> rested(bodies.size(), false);
  for (size_t k = 0; k < bodies.size(); ++k) {
    if (id[k] == SIZE_MAX) continue;
    rested[k] = body_motion(bodies[k], checked[k], now[k]) <= options.check_motion_m;
    if (!rested[k]) moved.push_back(world.bounds(id[k]));
  }
  const glm::dvec3 gap(options.resettle_gap_m);
  for (size_t k = 0; k < bodies.size(); ++k) {
    if (!rested[k]) continue;
    const auto [lo, hi] = world.bounds(id[k]);
    const bool near_motion = std::any_of(moved.begin(), moved.end(), [&](const auto& m) {
      return glm::all(glm::lessThanEqual(lo, m.second + gap)) &&
             glm::all(glm::lessThanEqual(m.first, hi + gap));
    });
    if (!near_motion) world.pin(id[k]);
  }
}

/// A world holding the bodies at `poses` (those placed), at rest; their ids in `id`.
std::unique_ptr<World> world_at(const std::vector<SettleBody>& bodies,
                                const std::vector<Placement>& poses, const Container& container,
                                const SettleOptions& options, std::vector<size_t>& id) {
  auto world = std::make_unique<World>(container, options);
  id.assign(bodies.size(), SIZE_MAX);
  for (size_t k = 0; k < bodies.size(); ++k) {
    if (poses[k].placed) id[k] = world->add_body(bodies[k], poses[k]);
  }
  return world;
}

}  // namespace

SettleResult settle_pieces(const std::vector<SettleBody>& bodies, const Container& container,
                           const SettleOptions& options) {
  SettleResult r;
  std::vector<Placement> drop_poses(bodies.size());
  double ceiling = 0.1;
  for (size_t k = 0; k < bodies.size(); ++k) {
    drop_poses[k] = bodies[k].drop;
    if (!bodies[k].drop.placed) continue;
    CUTAWAY_CHECK(bodies[k].shape != nullptr && bodies[k].density_kg_m3 > 0);
    ceiling = std::max(ceiling, 2 * centre_of_mass(bodies[k], bodies[k].drop).y + 0.1);
  }
  std::vector<size_t> id;
  std::vector<int> drops(bodies.size(), 0);
  auto world = world_at(bodies, drop_poses, container, options, id);
  settle_world(*world, bodies, id, drops, ceiling, options, r);
  // Not a step taken (max_seconds 0: only the check): the layout is the one given, exactly,
  // not its round trip through the world's transforms (they are single precision).
  r.placements = r.steps == 0 ? drop_poses : world->poses(bodies, id);
  // The stability check: the layout in a new world, at rest, run for verify_seconds. If a piece
  // moves more than check_motion_m the layout is not at rest without the contact impulses that
  // settling built up step after step (a settled salad sagged 6.7 mm when they were lost); it
  // settles on in that world, from where the check stopped, where the check found motion
  // (pin_resting), and is checked again. Stable: the kept check moved no corner more than
  // stable_motion_m.
  const int verify_steps =
      static_cast<int>(std::ceil(options.verify_seconds / options.time_step_s));
  const int check_every = steps_per_rest_check(options);
  SettleOptions verify = options;
  verify.solver_iterations = options.check_solver_iterations;
  // The best layout whose check ended within the limit, kept in case the last check does not
  // pass: settling on after a failed check can unsettle a piece that rested before (the market
  // stall's second check moved 0.58 mm, its third 6.9 mm).
  struct Checked {
    std::vector<Placement> placements;
    double motion_m = 0;
    int lost = 0, round = 0;
  };
  std::optional<Checked> best;
  for (int round = 1;; ++round) {
    world = world_at(bodies, r.placements, container, verify, id);
    r.verify_rounds = r.kept_round = round;
    r.stability_motion_m = 0;
    // Stopped early once over the limit: such a layout is never kept.
    for (int s = 1; s <= verify_steps && r.stability_motion_m <= options.stable_motion_m; ++s) {
      world->step();
      ++r.steps;
      if (s % check_every == 0 || s == verify_steps)
        r.stability_motion_m = largest_motion(bodies, r.placements, world->poses(bodies, id));
    }
    if (r.stability_motion_m <= options.check_motion_m) break;
    const bool better = r.stability_motion_m <= options.stable_motion_m &&
                        (!best || r.stability_motion_m < best->motion_m);
    // A round that moved more than the best check within the limit ends the rounds: settling on
    // unsettled what had rested (the salad's checks moved 0.56, 0.68 and 0.63 mm, and the first
    // was kept after two more rounds).
    const bool worse = best && !better;
    if (better) best = Checked{r.placements, r.stability_motion_m, r.lost, round};
    if (worse || round == options.max_verify_rounds) {
      if (best) {
        r.placements = std::move(best->placements);
        r.stability_motion_m = best->motion_m;
        r.lost = best->lost;
        r.kept_round = best->round;
      }
      break;
    }
    pin_resting(*world, bodies, id, r.placements, options);
    settle_world(*world, bodies, id, drops, ceiling, verify, r);
    r.placements = world->poses(bodies, id);
  }
  r.stable = r.stability_motion_m <= options.stable_motion_m;
  r.simulated_s = r.steps * options.time_step_s;
  return r;
}

}  // namespace cutaway
