// Uploading interleaved vertex data to OpenGL: one vertex array with a vertex buffer and an
// element buffer, the way every renderer in render/ draws its triangles. Internal to render/.
#pragma once

#include <glad/gl.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace cutaway {

/// One float vertex attribute: `components` floats at byte `offset` of each vertex.
struct VertexAttribute {
  GLuint location;
  GLint components;
  size_t offset;
};

/// Creates a vertex array with a vertex buffer of `vertex_bytes` bytes (`stride` bytes per
/// vertex) and an element buffer of `index_count` uint32 indices (none when 0), enables the
/// attributes, and leaves the vertex array bound. The objects belong to the current context,
/// which frees them with itself.
/// @pre a current OpenGL context
GLuint make_vertex_array(const void* vertices, size_t vertex_bytes, GLsizei stride,
                         const uint32_t* indices, size_t index_count,
                         std::initializer_list<VertexAttribute> attributes);

/// make_vertex_array over a vector of vertex structs and a vector of indices.
template <class Vertex>
GLuint make_vertex_array(const std::vector<Vertex>& vertices, const std::vector<uint32_t>& indices,
                         std::initializer_list<VertexAttribute> attributes) {
  return make_vertex_array(vertices.data(), vertices.size() * sizeof(Vertex),
                           static_cast<GLsizei>(sizeof(Vertex)), indices.data(), indices.size(),
                           attributes);
}

}  // namespace cutaway
