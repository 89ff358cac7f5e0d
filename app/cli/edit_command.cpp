// `cutaway edit`: the template editor's server (app/edit/edit_server.h), with the OpenGL previews
// as its pictures, until Ctrl-C.
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <glm/vec3.hpp>
#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/edit/edit_pictures.h"
#include "app/edit/edit_server.h"
#include "diffusion/diffusion.h"
#include "volume/volume_cost.h"

namespace cutaway::cli {

namespace {

/// How long a stop waits for requests still being computed before the process ends anyway.
constexpr std::chrono::seconds kStopGrace{2};

/// `cutaway edit TEMPLATE [--port N] [--volume-voxels N]`: serves the template
/// editor on 127.0.0.1 until interrupted. TEMPLATE need not exist yet (a new template).
struct EditArgs {
  std::string template_path = "new-template.yaml";  ///< opened, or made on the first Save
  int port = 8765;
  int volume_voxels = EditServerOptions{}.volume_voxels_across;  ///< the cutting page's grid
};

int run_edit(const EditArgs& a) {
  const std::filesystem::path path = std::filesystem::absolute(a.template_path);
  require_extension("TEMPLATE", a.template_path, ".yaml");
  if (!std::filesystem::is_directory(path.parent_path()))
    throw UsageError("TEMPLATE: the folder " + quoted(path.parent_path().string()) +
                     " does not exist");
  EditServerOptions options;
  options.template_path = path;
  options.port = a.port;
  options.volume_voxels_across = a.volume_voxels;
  EditServer server(options, opengl_edit_pictures());
  spdlog::info("cutaway edit: {} at http://127.0.0.1:{}/ (Ctrl-C stops)", path.string(),
               server.port());
  if (const std::optional<std::string> cutting = server.cutting_page_url())
    spdlog::info("cut it live at {}", *cutting);
  else
    spdlog::info("cut it live once it is saved and checks: /cut.html?volume=/api/volume/NAME.json"
                 "&model=/api/volume/NAME.glb, NAME its name (doc/editor.md)");
  // Ctrl-C or SIGTERM stops the server from a thread that waits for the signal. The server
  // ends its connections at once, but a request being computed (a check of a huge template)
  // would keep run() waiting: after kStopGrace the process ends without it. Saves are atomic,
  // so stopping never leaves a half-written template.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::mutex stopped_mutex;
  std::condition_variable stopped_changed;
  bool stopped = false;
  std::thread waiter([&] {
    int received = 0;
    sigwait(&signals, &received);
    server.stop();
    std::unique_lock<std::mutex> lock(stopped_mutex);
    if (!stopped_changed.wait_for(lock, kStopGrace, [&] { return stopped; })) {
      spdlog::warn("cutaway edit: stopped without waiting for a request still being computed");
      std::_Exit(0);
    }
  });
  server.run();
  {
    const std::lock_guard<std::mutex> lock(stopped_mutex);
    stopped = true;
  }
  stopped_changed.notify_all();
  pthread_kill(waiter.native_handle(), SIGTERM);  // wakes it if run() ended without a signal
  waiter.join();
  return 0;
}

}  // namespace

Command add_edit_command(CLI::App& app) {
  auto args = std::make_shared<EditArgs>();
  CLI::App* edit = app.add_subcommand(
      "edit", "the template editor in the browser: a local server on 127.0.0.1 (doc/editor.md)");
  edit->add_option("TEMPLATE", args->template_path,
                   "template file (.yaml); may be new (default new-template.yaml here)");
  edit->add_option("--port", args->port,
                   "port on 127.0.0.1 (default 8765; 0: any free port, printed)")
      ->check(number_rule(0, 65535));
  // The page's volumes (the default cube) within the cost of every volume, whatever the skin's
  // shape.
  edit->add_option("--volume-voxels", args->volume_voxels,
                   "voxels along the longest edge of the cutting page's interior volume")
      ->check(number_rule(4, most_voxels_across(glm::dvec3(1), DiffusionOptions{}.cube_size)));
  return {edit, [args](const Common&, OutputSet&) { return run_edit(*args); }};
}

}  // namespace cutaway::cli
