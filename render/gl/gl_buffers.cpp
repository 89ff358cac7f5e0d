#include "render/gl/gl_buffers.h"

namespace cutaway {

GLuint make_vertex_array(const void* vertices, size_t vertex_bytes, GLsizei stride,
                         const uint32_t* indices, size_t index_count,
                         std::initializer_list<VertexAttribute> attributes) {
  GLuint vertex_array = 0, buffers[2] = {0, 0};
  glGenVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
  glGenBuffers(index_count > 0 ? 2 : 1, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_bytes), vertices, GL_STATIC_DRAW);
  if (index_count > 0) {
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(index_count * sizeof(uint32_t)),
                 indices, GL_STATIC_DRAW);
  }
  for (const VertexAttribute& a : attributes) {
    glEnableVertexAttribArray(a.location);
    glVertexAttribPointer(a.location, a.components, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(a.offset));
  }
  return vertex_array;
}

}  // namespace cutaway
