#include "model/crossing_test.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

namespace cutaway {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 cgal_point(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

struct CrossingTest::Impl {
  Triangles triangles;
  std::vector<size_t> first;  // index of each surface's first triangle
  Tree tree;
};

CrossingTest::CrossingTest(const std::vector<const DsMesh*>& surfaces)
    : impl_(std::make_unique<Impl>()) {
  for (const DsMesh* mesh : surfaces) {
    impl_->first.push_back(impl_->triangles.size());
    for (auto fh : mesh->faces()) {
      std::array<Kernel::Point_3, 3> p;
      int k = 0;
      for (auto vh : mesh->fv_range(fh)) p[k++] = cgal_point(to_glm(mesh->point(vh)));
      impl_->triangles.emplace_back(p[0], p[1], p[2]);
    }
  }
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
}

CrossingTest::~CrossingTest() = default;

int CrossingTest::crossed(const std::vector<std::array<glm::dvec3, 3>>& triangles) const {
  if (impl_->triangles.empty()) return -1;
  for (const auto& t : triangles) {
    const Triangle query(cgal_point(t[0]), cgal_point(t[1]), cgal_point(t[2]));
    if (query.is_degenerate()) continue;
    if (const auto hit = impl_->tree.any_intersected_primitive(query)) {
      const size_t i = static_cast<size_t>(*hit - impl_->triangles.cbegin());
      const auto after = std::upper_bound(impl_->first.begin(), impl_->first.end(), i);
      return static_cast<int>(after - impl_->first.begin()) - 1;
    }
  }
  return -1;
}

}  // namespace cutaway
