// Renders a POV-Ray scene file to PNG with the system's `povray` (POV-Ray 3.7, Debian package
// povray, installed by scripts/install-deps.sh), as a child process without a shell.
#pragma once

#include <filesystem>
#include <string>

namespace cutaway {

/// How render_povray() runs POV-Ray.
struct PovrayOptions {
  bool antialias = true;  ///< adaptive supersampling: +A0.3 +AM2 +R3; off: -A
  int quality = 9;        ///< POV-Ray's +Q, 0..11 (9: everything but radiosity)
  int threads = 0;        ///< render threads (+WT); 0 = POV-Ray's default (one per core)
  std::string executable = "povray";  ///< a name looked up in PATH, or a path
};

/// Renders `pov_file` to a PNG of width x height pixels at `png_out`.
///
/// Debian's /etc/povray/3.7/povray.conf restricts POV-Ray's file I/O to a few trees, the
/// current directory among them; so the scene is copied into a fresh temporary directory
/// (under std::filesystem::temp_directory_path()), POV-Ray runs there (fork + chdir + execvp,
/// no shell, stdin from /dev/null, stdout and stderr captured) with
///   +Iscene.pov +Oscene.png +FN +W<width> +H<height> -D -P -V -GS -GR +Q<quality>
///   File_Gamma=sRGB [+A0.3 +AM2 +R3 | -A] [+WT<threads>]
/// (PNG output, no display, no pause, no progress or statistics; fatal errors and warnings are
/// kept), and the PNG is then written to `png_out` atomically (write_file_atomically(): a
/// failed run leaves no partial file and an existing `png_out` untouched). The temporary
/// directory is removed in every case, also when SIGTERM, SIGINT or SIGHUP stops the process
/// (RemoveOnSignal); POV-Ray itself gets SIGTERM when the calling thread ends (PR_SET_PDEATHSIG:
/// call this from a thread that outlives the render, e.g. the main thread). The PNG is 8-bit RGB,
/// sRGB-encoded (a scene written with `assumed_gamma 1.0` and linear colours, as scene_to_pov()
/// writes, comes out right).
///
/// The scene is rendered away from its own directory, with that directory on POV-Ray's
/// library path (+L): files it names by relative name (image_map textures written beside it)
/// are found there, besides POV-Ray's standard include files (colors.inc, ...).
///
/// @param pov_file  a readable POV-Ray scene file
/// @param png_out   where the PNG goes; missing parent directories are created
/// @param width, height  image size in pixels, 1..16384 each
/// @param options   quality in 0..11, threads >= 0
/// @throws InternalError when the size or options are out of range
/// @throws EnvironmentError when the scene cannot be read, `povray` cannot be started (not
///         installed), exits with an error or is killed, or writes no image; the message holds
///         the last lines POV-Ray printed
void render_povray(const std::filesystem::path& pov_file, const std::filesystem::path& png_out,
                   int width, int height, const PovrayOptions& options);

}  // namespace cutaway
