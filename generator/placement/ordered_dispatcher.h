// Bullet's narrow phase on several threads, with the serial dispatcher's results. Each step,
// Bullet's collision dispatcher computes the contacts of every overlapping pair of bodies (for
// a heap of hundreds of pieces, three quarters of the settling's time). The pairs do not depend
// on one another: each has its own collision algorithm and contact manifolds. What does depend
// on the order is the dispatcher's list of manifolds, which the constraint solver walks in
// order: Bullet's own multithreaded dispatcher appends the manifolds made during a step in the
// order the threads happened to make them, and the solver's results then vary from run to run.
// Here every pair records the manifolds its collision algorithm makes and releases, and after
// the parallel pass the records are applied to the list pair by pair, in the pair cache's order:
// the list, and so the whole simulation, is the serial dispatcher's to the bit, whatever the
// thread count.
#pragma once

#include <mutex>
#include <vector>

#include <btBulletCollisionCommon.h>

namespace cutaway {

/// A btCollisionDispatcher whose dispatchAllCollisionPairs processes the overlapping pairs on
/// TBB's threads and leaves the same manifolds in the same order as btCollisionDispatcher
/// (serially where the thread limit is 1, there are fewer than 16 pairs, or the query is not
/// the discrete one, whose near callbacks write only to their own pair). Outside that pass
/// (pairs removed by the broadphase, bodies removed) it is btCollisionDispatcher. Bullet's pool
/// allocators do not lock where Bullet is built without BT_THREADSAFE (Debian's): this
/// dispatcher takes its pools under a lock of its own.
class OrderedDispatcher : public btCollisionDispatcher {
 public:
  explicit OrderedDispatcher(btCollisionConfiguration* configuration);

  btPersistentManifold* getNewManifold(const btCollisionObject* body0,
                                       const btCollisionObject* body1) override;
  void releaseManifold(btPersistentManifold* manifold) override;
  void dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                 btDispatcher* dispatcher) override;
  void* allocateCollisionAlgorithm(int size) override;
  void freeCollisionAlgorithm(void* memory) override;

 private:
  /// A manifold made (`made`) or released by a pair's algorithm during the parallel pass.
  struct Change {
    btPersistentManifold* manifold;
    bool made;
  };
  /// Adds `manifold` to the list, as btCollisionDispatcher::getNewManifold does.
  void append(btPersistentManifold* manifold);

  /// Where getNewManifold and releaseManifold record while this thread processes a pair of a
  /// parallel pass: the dispatcher and that pair's changes (null outside a pass).
  struct Recording {
    const OrderedDispatcher* dispatcher = nullptr;
    std::vector<Change>* changes = nullptr;
  };
  static thread_local Recording recording_;
  std::mutex pools_;  ///< held while taking from or giving back to Bullet's pool allocators

  std::vector<std::vector<Change>> changes_;  ///< per pair of the pass running
};

}  // namespace cutaway
