// Compiling and linking GLSL programs from the embedded shaders (render/gl/shader_sources.h).
// Internal to render/: it needs the glad loader header, which is not exported.
#pragma once

#include <glad/gl.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace cutaway {

/// An owned GL program object; deletes it on destruction. Needs a current context for its whole
/// life. Neither copyable nor movable.
class GlProgram {
 public:
  /// Compiles shaders/VERTEX_FILE and shaders/FRAGMENT_FILE (embedded at build time) and links
  /// them.
  /// @param vertex_file, fragment_file bare file names, e.g. "preview.vert"
  /// @throws EnvironmentError naming the file, with the driver's info log, on a compile or
  ///         link error, or when a file was not embedded
  GlProgram(std::string_view vertex_file, std::string_view fragment_file);
  /// Compiles shaders/COMPUTE_FILE (e.g. "pmvc_reduce.comp") and links it alone.
  /// @throws EnvironmentError as the two-stage constructor
  explicit GlProgram(std::string_view compute_file);
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  ~GlProgram();

  /// The GL program name, for glUseProgram and glGetUniformLocation.
  GLuint id() const { return id_; }

  /// The location of a uniform that the program must use.
  /// @throws InternalError when the linked program has no active uniform of that name
  GLint uniform(const char* name) const;

 private:
  /// Links the compiled shaders into id_ (deleting them); `files` names them for errors.
  void link(std::initializer_list<GLuint> shaders, const std::string& files);
  GLuint id_ = 0;
};

}  // namespace cutaway
