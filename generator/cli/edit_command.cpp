// `cutaway edit`: the template editor's server (edit/edit_server.h), with the OpenGL previews
// as its pictures, until Ctrl-C.
#include <csignal>
#include <filesystem>
#include <thread>

#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "edit/edit_server.h"
#include "render/edit_pictures.h"

namespace cutaway::cli {

int run_edit(const EditArgs& a) {
  const std::filesystem::path path = std::filesystem::absolute(a.template_path);
  require_extension("TEMPLATE", a.template_path, ".yaml");
  if (!std::filesystem::is_directory(path.parent_path()))
    throw UsageError("TEMPLATE: the folder " + quoted(path.parent_path().string()) +
                     " does not exist");
  EditServerOptions options;
  options.template_path = path;
  options.port = a.port;
  EditServer server(options, opengl_edit_pictures());
  spdlog::info("cutaway edit: {} at http://127.0.0.1:{}/ (Ctrl-C stops)", path.string(),
               server.port());
  // Ctrl-C or SIGTERM stops the server from a thread that waits for the signal; saves are
  // atomic, so stopping never leaves a half-written template.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread waiter([&] {
    int received = 0;
    sigwait(&signals, &received);
    server.stop();
  });
  server.run();
  if (waiter.joinable()) {
    pthread_kill(waiter.native_handle(), SIGTERM);
    waiter.join();
  }
  return 0;
}

}  // namespace cutaway::cli
