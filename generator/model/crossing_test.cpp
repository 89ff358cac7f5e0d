#include "model/crossing_test.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <iterator>

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
  // with_blur_sheets: the blurred surfaces' own triangles, each with the largest blur of its
  // corners (metres), and the largest blur of all.
  Triangles blurred;
  std::vector<double> blur;
  double max_blur = 0;
  Tree blurred_tree;
};

CrossingTest::CrossingTest(const std::vector<const DsMesh*>& surfaces, bool with_blur_sheets)
    : impl_(std::make_unique<Impl>()) {
  for (const DsMesh* mesh : surfaces) {
    impl_->first.push_back(impl_->triangles.size());
    std::vector<glm::dvec3> normals;
    if (with_blur_sheets && is_blurred(*mesh)) normals = vertex_normals(*mesh);
    // The surface itself, then its blur's two sheets where PMVC draws them (blur_sheet_point).
    for (const int sign : {0, 1, -1}) {
      if (sign != 0 && normals.empty()) break;
      for (auto fh : mesh->faces()) {
        std::array<Kernel::Point_3, 3> p;
        double blur = 0;
        int k = 0;
        for (auto vh : mesh->fv_range(fh)) {
          p[k++] = cgal_point(blur_sheet_point(*mesh, normals, vh, sign));
          blur = std::max(blur, mesh->data(vh).blur);
        }
        impl_->triangles.emplace_back(p[0], p[1], p[2]);
        if (sign == 0 && !normals.empty() && blur > 0) {
          impl_->blurred.emplace_back(p[0], p[1], p[2]);
          impl_->blur.push_back(blur);
          impl_->max_blur = std::max(impl_->max_blur, blur);
        }
      }
    }
  }
  if (!impl_->blurred.empty()) {
    impl_->blurred_tree.insert(impl_->blurred.cbegin(), impl_->blurred.cend());
    impl_->blurred_tree.build();
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

CrossingTest::Nearest CrossingTest::nearest(const glm::dvec3& p) const {
  if (impl_->triangles.empty()) return {INFINITY, -1};
  const auto [closest, id] = impl_->tree.closest_point_and_primitive(cgal_point(p));
  const size_t i = static_cast<size_t>(id - impl_->triangles.cbegin());
  const auto after = std::upper_bound(impl_->first.begin(), impl_->first.end(), i);
  return {std::sqrt(CGAL::squared_distance(cgal_point(p), closest)),
          static_cast<int>(after - impl_->first.begin()) - 1};
}

bool CrossingTest::within_blur(const glm::dvec3& p) const {
  if (impl_->blurred.empty()) return false;
  const Kernel::Point_3 q = cgal_point(p);
  // The triangles that reach the box around the ball of the largest blur: every one within its
  // own blur of p is among them. Not CGAL's Sphere_3: it is the sphere's surface, so a triangle
  // wholly inside the ball was never tested (a kiwi seed sat in the blur of the locule walls'
  // fine triangles), and its exact test against a triangle fell back to multiprecision
  // arithmetic (most of a kiwi variant's time).
  const double r = impl_->max_blur;
  const CGAL::Bbox_3 box(p.x - r, p.y - r, p.z - r, p.x + r, p.y + r, p.z + r);
  std::vector<Tree::Primitive_id> near;
  impl_->blurred_tree.all_intersected_primitives(box, std::back_inserter(near));
  for (const auto id : near) {
    const size_t i = static_cast<size_t>(id - impl_->blurred.cbegin());
    if (CGAL::squared_distance(q, impl_->blurred[i]) < impl_->blur[i] * impl_->blur[i]) return true;
  }
  return false;
}

}  // namespace cutaway
