// `cutaway edit`: a local web server for the template editor (doc/editor.md). The browser page
// sends the template's text; the server answers with what the same library the command line
// uses makes of it: the parser's and checks' verdict (file, line, column, field, rule), a
// picture of the see-through DS model, a cross-section at a height, and the saved file.
//
// Security, as for any local server: it listens on 127.0.0.1 only; requests whose Host or
// Origin is not the server's own are refused (DNS rebinding, cross-site pages); every request
// to /api/ must carry the server's token (a random one per server, which only the pages it
// serves hold), so that a page of another origin cannot make it work; it serves a fixed set of
// embedded files and reads and writes only the one template file it was started on (no path
// comes from a request), and only while it is a regular file. The cutting page (/cut.html)
// cuts that file's template live from its interior volume (POST /api/volume/...).
//
// Bounds, so that no client, however slow or large its requests, stops the others being
// answered: request bodies are limited in size whatever their transfer encoding (compressed
// ones are refused); a request must arrive within a time limit of its first byte; connections
// are served each on its own thread, up to a bound; work (volumes, model pictures, skins, cuts,
// variant strips) is queued with a small bound, one request at a time per view of the pages,
// a newer request of a view replacing the older; checks and saves never wait behind work.
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "app/edit/web_libraries.h"
#include "base/outcome.h"
#include "base/plane.h"
#include "model/ds_model.h"
#include "section/cross_section.h"

namespace cutaway {

/// What the editor asks of the library for one version of the template text, without HTTP.
/// `template_path` is the file being edited: messages name it and `mesh` surfaces' files are
/// relative to its folder.
///
/// The verdict on `text`: {"ok": true, "surfaces": N, "bbox_min": [x, y, z], "bbox_max":
/// [...], "curves": [...]} (template units) when it parses and its model builds, else {"ok":
/// false, "file", "line", "column", "field", "rule", "message"} (InputError's parts; line and
/// column 1-based). "curves" has one entry per surface, {"profile": [[r, y], ...], "sections":
/// [[[x, z], ...], ...]}: the curves as the library fits them (curves.h fit_curve), which the
/// page draws over the points the user sketched; a `circle` section and a mesh surface give
/// no sections, a mesh no profile.
/// @throws nothing for bad text; std::bad_alloc and InternalError pass through
nlohmann::json check_template_text(std::string_view text,
                                   const std::filesystem::path& template_path);

/// Pictures the editor shows, rendered by the caller's renderers (the OpenGL previews live in
/// render/, which the library does not include): PNG bytes.
struct EditRenderers {
  std::function<std::string(const DsModel&)> model_png;         ///< the see-through model
  std::function<std::string(const CrossSection&)> section_png;  ///< one cut face, head-on
  /// The mid-height cuts of seeded variants side by side (a missing one: an empty tile).
  std::function<std::string(std::vector<Outcome<CrossSection>>)> variants_png;
};

/// The most bytes of a request's line and headers (above that: 400, and the connection is closed).
inline constexpr size_t kMaxRequestHeadBytes = 64u << 10;
/// The most requests served on one connection before it is closed (the client opens another).
inline constexpr int kRequestsPerConnection = 100;
/// The header that carries the server's token (EditServer::token()) on requests to /api/.
inline constexpr std::string_view kTokenHeader = "X-Cutaway-Token";

/// How EditServer listens and what it bounds.
struct EditServerOptions {
  std::filesystem::path template_path;  ///< the file edited and saved; its folder must exist
  int port = 8765;                      ///< on 127.0.0.1; 0: any free port
  /// Larger request bodies are refused (413), chunked ones as soon as they pass it; their chunk
  /// framing may add at most kMaxRequestHeadBytes.
  size_t max_body_bytes = 4u << 20;
  /// Connections served at once; one more is answered 503 and closed.
  int max_connections = 256;
  /// A request, head and body, must arrive within this of its first byte (else the connection
  /// is closed, after a 400, or 408 when the head had arrived); it is also how long each write
  /// of an answer may wait for the client to take it.
  std::chrono::milliseconds request_timeout{5000};
  /// How long a connection may wait for its next request (keep-alive) or its first one.
  std::chrono::milliseconds idle_timeout{5000};
  int section_cube = 8;         ///< PMVC cube-map size of the live cross-section
  int coarse_section_cube = 3;  ///< the same while the user drags the plane
  int variant_cube = 8;         ///< PMVC cube-map size of the variants' cuts
  /// Voxels along the skin's longest edge of the cutting page's volume (POST /api/volume/...;
  /// 4 up to the most volume_cost.h's bound allows any skin at the default cube): coarser than
  /// `cutaway volume`'s default, so the page opens in seconds.
  int volume_voxels_across = 64;
  /// Work requests (volume, model picture and glTF, skin, cut, variants) admitted at once,
  /// running or waiting; one more is answered 503 with Retry-After at once.
  int max_work_requests = 4;
  std::vector<WebLibrary> libraries = editor_libraries();  ///< served at /lib/NAME/
};

/// What the server's work queue has done since it started (EditServer::work_counts()): work
/// requests are those that compute (volume, model picture and glTF, skin, cut, variants).
struct EditWorkCounts {
  int running = 0;          ///< work requests being computed now
  int waiting = 0;          ///< work requests admitted, waiting for their view's turn
  int finished = 0;         ///< work requests that ran (whatever they answered)
  int superseded = 0;       ///< answered 409: a newer request of their view replaced them
  int turned_away = 0;      ///< answered 503: the queue held max_work_requests
  int volumes_sampled = 0;  ///< interior volumes sampled for the cutting page
};

/// Passes when a request may be served, else fails with why not (403): its Host header must
/// name this server (127.0.0.1:PORT or localhost:PORT), and its Origin header, when present,
/// must be http://127.0.0.1:PORT or http://localhost:PORT.
Check check_request(std::string_view host, std::string_view origin, int port);

/// The editor's server: binds at construction, serves in run(), stops from any thread.
/// HTTP is cpp-httplib's (its routing and request parsing); the connections are this class's:
/// it accepts them (listen backlog 512) and serves each on a thread of its own, with the
/// bounds of EditServerOptions.
class EditServer {
 public:
  /// Binds 127.0.0.1:options.port and listens.
  /// @pre options.max_connections >= 1, options.max_work_requests >= 1, the timeouts > 0
  /// @throws EnvironmentError "port N on 127.0.0.1 is taken; pass another with --port" when
  ///         it cannot bind
  /// @throws std::system_error when the system gives no random bytes for the token
  EditServer(EditServerOptions options, EditRenderers renderers);
  /// @pre run() has returned, or was never called
  ~EditServer();
  EditServer(const EditServer&) = delete;
  EditServer& operator=(const EditServer&) = delete;

  int port() const;  ///< the bound port
  /// The server's token: 32 hex digits from the system's random source, new for each server.
  /// The pages it serves hold it (a meta tag named cutaway-token) and send it in kTokenHeader;
  /// a request to /api/ without it is refused (403) before any of its work.
  const std::string& token() const;
  /// The work queue's counts so far; from any thread.
  EditWorkCounts work_counts() const;
  /// The address of the cutting page of the template as saved (doc/editor.md, The cutting
  /// page): http://127.0.0.1:PORT/cut.html?volume=/api/volume/NAME.json&model=/api/volume/NAME.glb
  /// with NAME the saved template's `name`; nothing while the file is missing, unreadable or
  /// does not parse. Reads and parses the file; from any thread.
  std::optional<std::string> cutting_page_url() const;
  /// Serves until stop(); blocks; returns at once after a stop(). Before returning it closes
  /// the listening socket and waits for the connections' threads: requests being read or
  /// written end at once (their sockets are shut down), a variants strip being made stops
  /// after the variant it is on, and any other request being computed is finished (its answer
  /// then goes nowhere).
  void run();
  /// Makes run() return (or a later run() return at once); from any thread, any number of times.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
