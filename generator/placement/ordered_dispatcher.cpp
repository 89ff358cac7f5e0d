#include "placement/ordered_dispatcher.h"

#include <new>
#include <vector>

#include <LinearMath/btPoolAllocator.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

namespace cutaway {

thread_local OrderedDispatcher::Recording OrderedDispatcher::recording_;

OrderedDispatcher::OrderedDispatcher(btCollisionConfiguration* configuration)
    : btCollisionDispatcher(configuration) {}

btPersistentManifold* OrderedDispatcher::getNewManifold(const btCollisionObject* body0,
                                                        const btCollisionObject* body1) {
  if (recording_.dispatcher != this) return btCollisionDispatcher::getNewManifold(body0, body1);
  // btCollisionDispatcher::getNewManifold's manifold, not yet in the list.
  const auto breaking_of = [](const btCollisionObject* body) {
    return body->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold);
  };
  const btScalar breaking = (m_dispatcherFlags & CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD)
                                ? btMin(breaking_of(body0), breaking_of(body1))
                                : gContactBreakingThreshold;
  const btScalar processing =
      btMin(body0->getContactProcessingThreshold(), body1->getContactProcessingThreshold());
  void* memory = nullptr;
  {
    const std::lock_guard<std::mutex> lock(pools_);
    memory = m_persistentManifoldPoolAllocator->allocate(sizeof(btPersistentManifold));
  }
  if (!memory) memory = btAlignedAlloc(sizeof(btPersistentManifold), 16);
  auto* manifold = new (memory) btPersistentManifold(body0, body1, 0, breaking, processing);
  recording_.changes->push_back({manifold, true});
  return manifold;
}

void OrderedDispatcher::releaseManifold(btPersistentManifold* manifold) {
  if (recording_.dispatcher != this) return btCollisionDispatcher::releaseManifold(manifold);
  recording_.changes->push_back({manifold, false});
}

void* OrderedDispatcher::allocateCollisionAlgorithm(int size) {
  const std::lock_guard<std::mutex> lock(pools_);
  return btCollisionDispatcher::allocateCollisionAlgorithm(size);
}

void OrderedDispatcher::freeCollisionAlgorithm(void* memory) {
  const std::lock_guard<std::mutex> lock(pools_);
  btCollisionDispatcher::freeCollisionAlgorithm(memory);
}

void OrderedDispatcher::append(btPersistentManifold* manifold) {
  manifold->m_index1a = m_manifoldsPtr.size();
  m_manifoldsPtr.push_back(manifold);
}

void OrderedDispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairs,
                                                  const btDispatcherInfo& info,
                                                  btDispatcher* dispatcher) {
  const int count = pairs->getNumOverlappingPairs();
  // Serially where there are no threads to share the pairs or too few pairs to share, where
  // Bullet would sort the pairs first, and for time of impact (each pair lowers one shared
  // value).
  if (oneapi::tbb::this_task_arena::max_concurrency() == 1 || count < 16 ||
      info.m_deterministicOverlappingPairs ||
      info.m_dispatchFunc != btDispatcherInfo::DISPATCH_DISCRETE) {
    btCollisionDispatcher::dispatchAllCollisionPairs(pairs, info, dispatcher);
    return;
  }
  btBroadphasePair* pair = pairs->getOverlappingPairArrayPtr();
  if (changes_.size() < static_cast<size_t>(count)) changes_.resize(static_cast<size_t>(count));
  const btNearCallback near = getNearCallback();
  oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<int>(0, count, 8),
                            [&](const oneapi::tbb::blocked_range<int>& r) {
                              const Recording before = recording_;
                              for (int i = r.begin(); i != r.end(); ++i) {
                                recording_ = {this, &changes_[static_cast<size_t>(i)]};
                                near(pair[i], *this, info);
                              }
                              recording_ = before;
                            });
  // The list as the serial pass leaves it: each pair's changes in the order it made them,
  // pair after pair.
  for (int i = 0; i < count; ++i) {
    std::vector<Change>& changes = changes_[static_cast<size_t>(i)];
    for (const Change& c : changes) {
      if (c.made) append(c.manifold);
      else btCollisionDispatcher::releaseManifold(c.manifold);
    }
    changes.clear();
  }
}

}  // namespace cutaway
