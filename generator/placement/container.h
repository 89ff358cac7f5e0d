// What a scene's pieces are placed in or on (doc/scene-format.md, `container` and `arrange`):
// plain data that the layout, the physics and the container's mesh read.
#pragma once

#include <glm/vec3.hpp>

namespace cutaway {

/// How an item's pieces are arranged in the container (doc/scene-format.md, `arrange`).
enum class Arrangement {
  Pile,      ///< dropped onto the container and the pieces before them, then settled
  Fan,       ///< each object's pieces in a fanned row, each overlapping the one before
  Scatter,   ///< spread apart over the container, none resting on another
  Together,  ///< as Scatter, each object's pieces side by side (a fruit's halves together)
};

/// Whether pieces so arranged are scattered (Scatter, Together): laid apart on free ground.
inline bool is_scattered(Arrangement a) {
  return a == Arrangement::Scatter || a == Arrangement::Together;
}

/// The kinds of container of the scene format; none: the pieces lie on the floor.
enum class ContainerType { Bowl, Plate, Board, None };

/// What the pieces rest in or on. Bowl and plate are round (diameter, height); the board is a
/// box (width along X, depth along Z, height). Metres.
struct Container {
  ContainerType type = ContainerType::None;
  double diameter_m = 0;             ///< bowl, plate: outer rim diameter
  double width_m = 0;                ///< board: along X
  double depth_m = 0;                ///< board: along Z
  double height_m = 0;               ///< bowl, plate, board: total height
  glm::dvec3 colour{0.9, 0.9, 0.9};  ///< linear RGB
};

}  // namespace cutaway
