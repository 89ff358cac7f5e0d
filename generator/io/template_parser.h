// Reads and validates templates (doc/template-format.md, all of it). Every broken rule, the
// geometric ones included, is an InputError "FILE:LINE:COL: field.path: rule".
#pragma once

#include <string>
#include <string_view>

#include "model/template.h"

namespace cutaway {

/// Parses and validates template text.
/// @param text      the file's bytes (YAML 1.2 or JSON, UTF-8)
/// @param file      the name used in messages
/// @param base_dir  the directory `mesh` surfaces' `file` paths are relative to
/// @return the template in metres, linear RGB and radians, with the meshes of its `mesh`
///         surfaces read (read_mesh_file): nothing after parsing reads a file
/// @throws InputError for any rule of the format that the text breaks (syntax, unknown fields,
///         types, ranges, and the curve rules checked by check_template_curves), and for a
///         mesh file read_mesh_file refuses
Template parse_template(std::string_view text, const std::string& file,
                        const std::string& base_dir);

/// Reads the template file at `path` and parses it (base_dir = its directory).
/// @param text  when given, receives the file's bytes (asset fingerprints hash them)
/// @throws InputError as parse_template, and when the file cannot be read
Template load_template(const std::string& path, std::string* text = nullptr);

}  // namespace cutaway
