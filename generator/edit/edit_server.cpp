#include "edit/edit_server.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>
#include <thread>
#include <stdexcept>
#include <utility>

#include <httplib.h>
#include <sys/socket.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "diffusion/diffusion.h"
#include "edit/web_files.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "model/curves.h"
#include "model/model_builder.h"
#include "batch/variant_set.h"
#include "variation/grains.h"
#include "variation/variation.h"

namespace cutaway {

namespace {

/// A parsed template and its DS model.
struct Built {
  Template tmpl;
  DsModel model;
};

Built build(std::string_view text, const std::filesystem::path& template_path) {
  Template tmpl = parse_template(text, template_path.filename().string(),
                                 template_path.parent_path().string());
  DsModel model = build_model(tmpl);
  check_grain_limits(tmpl, model);  // as `cutaway check` does
  return {std::move(tmpl), std::move(model)};
}

nlohmann::json verdict_of(const InputError& e) {
  return {{"ok", false},          {"file", e.loc().file}, {"line", e.loc().line},
          {"column", e.loc().column}, {"field", e.field()},  {"rule", e.rule()},
          {"message", e.what()}};
}

nlohmann::json vec3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

/// `points` (metres) fitted as the template means them, in template units.
nlohmann::json fitted(const Polyline2& points, bool closed, bool smooth, double units) {
  nlohmann::json out = nlohmann::json::array();
  for (const glm::dvec2& p : fit_curve(points, closed, smooth)) out.push_back({p.x / units, p.y / units});
  return out;
}

/// The fitted profile and section loops of every surface (check_template_text's "curves").
nlohmann::json fitted_curves(const Template& t) {
  nlohmann::json curves = nlohmann::json::array();
  for (const SurfaceSpec& s : t.surfaces) {
    nlohmann::json c = {{"profile", nlohmann::json::array()}, {"sections", nlohmann::json::array()}};
    if (s.kind != SurfaceKind::Mesh) {
      c["profile"] = fitted(s.profile, s.kind == SurfaceKind::Within, s.smooth, t.metres_per_unit);
      for (const auto& loop : s.section.loops)
        c["sections"].push_back(fitted(loop, true, s.smooth, t.metres_per_unit));
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

/// The verdict on a template that parsed and built.
nlohmann::json verdict_of(const Built& b) {
  const double units = b.tmpl.metres_per_unit;
  return {{"ok", true},
          {"surfaces", b.model.surfaces.size()},
          {"bbox_min", vec3(b.model.bbox_min / units)},
          {"bbox_max", vec3(b.model.bbox_max / units)},
          {"curves", fitted_curves(b.tmpl)}};
}

void reply_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

/// Runs `answer`; an InputError becomes 422 with the verdict, any other error 500 with its
/// message.
void answer_or_refuse(httplib::Response& res, const std::function<void()>& answer) {
  try {
    answer();
  } catch (const InputError& e) {
    reply_json(res, 422, verdict_of(e));
  } catch (const std::exception& e) {
    reply_json(res, 500, {{"ok", false}, {"message", e.what()}});
  }
}

}  // namespace

nlohmann::json check_template_text(std::string_view text,
                                   const std::filesystem::path& template_path) {
  try {
    return verdict_of(build(text, template_path));
  } catch (const InputError& e) {
    return verdict_of(e);
  }
}

std::string request_refusal(std::string_view host, std::string_view origin, int port) {
  const std::string p = std::to_string(port);
  if (host != "127.0.0.1:" + p && host != "localhost:" + p)
    return "the Host header must be 127.0.0.1:" + p + " or localhost:" + p + ", not " +
           quoted(host);
  if (!origin.empty() && origin != "http://127.0.0.1:" + p && origin != "http://localhost:" + p)
    return "requests from other sites are refused (Origin " + quoted(origin) + ")";
  return "";
}

struct EditServer::Impl {
  EditServerOptions options;
  EditRenderers renderers;
  httplib::Server server;
  int port = 0;
  std::mutex work;  // one request at a time touches the library and OpenGL
  std::mutex state;  // guards the two flags below
  bool stop_requested = false;
  bool serving = false;  // run() is in httplib's listen loop, or about to enter it
  // The last text that built, with its template and model, and the cpu backend of its cuts
  // (made at the first cut): the page asks for the verdict, the model picture and cuts at
  // several heights of one text, which are built once. Guarded by `work`.
  std::string built_text;
  std::optional<Built> built;
  std::unique_ptr<DiffusionBackend> section_backend, coarse_section_backend;

  /// The template and model of `text`, from the last request when it sent the same text.
  /// @throws InputError as build()
  const Built& built_for(const std::string& text) {
    if (!built || text != built_text) {
      built.reset();
      section_backend.reset();
      coarse_section_backend.reset();
      built = build(text, options.template_path);
      built_text = text;
    }
    return *built;
  }

  /// Runs `answer` for a request about the template text in its body, as answer_or_refuse().
  void handle(const httplib::Request& req, httplib::Response& res,
              const std::function<void(const Built&)>& answer) {
    const std::lock_guard<std::mutex> lock(work);
    answer_or_refuse(res, [&] { answer(built_for(req.body)); });
  }
};

EditServer::EditServer(EditServerOptions options, EditRenderers renderers)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.options = std::move(options);
  s.renderers = std::move(renderers);
  s.server.set_payload_max_length(s.options.max_body_bytes);
  // httplib's default socket options add SO_REUSEPORT, with which a second process could bind
  // the same port and take the editor's requests; SO_REUSEADDR alone lets a restarted editor
  // take its port back from connections still closing, and a taken port fails to bind.
  s.server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  s.server.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
    const std::string why =
        request_refusal(req.get_header_value("Host"), req.get_header_value("Origin"), s.port);
    if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
    reply_json(res, 403, {{"ok", false}, {"message", why}});
    return httplib::Server::HandlerResponse::Handled;
  });
  // The page: embedded files (no request names a file on disk), and the libraries it
  // imports, each from its own folder (library_file keeps requests inside it).
  s.server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(editor_web_file("index.html")), "text/html; charset=utf-8");
  });
  s.server.Get(R"(/([a-z_]+)\.(js|css))", [](const httplib::Request& req, httplib::Response& res) {
    const std::string type = req.matches[2] == "js" ? "text/javascript" : "text/css";
    try {
      const std::string file = req.matches[1].str() + "." + req.matches[2].str();
      res.set_content(std::string(editor_web_file(file)), type + "; charset=utf-8");
    } catch (const std::runtime_error&) {
      reply_json(res, 404, {{"ok", false}, {"message", "no such file"}});
    }
  });
  s.server.Get(R"(/lib/([a-z]+)/(.+))", [&s](const httplib::Request& req, httplib::Response& res) {
    for (const WebLibrary& lib : s.options.libraries) {
      if (lib.name != req.matches[1]) continue;
      if (const auto file = library_file(lib.folder, req.matches[2].str())) {
        res.set_content(read_file_bytes(*file), "text/javascript; charset=utf-8");
        return;
      }
    }
    reply_json(res, 404, {{"ok", false}, {"message", "no such library file"}});
  });

  s.server.Get("/api/template", [&s](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(s.work);
    const std::filesystem::path& path = s.options.template_path;
    std::error_code ec;
    const bool exists = std::filesystem::exists(path, ec);
    reply_json(res, 200,
               {{"file", path.filename().string()},
                {"exists", exists},
                {"text", exists ? read_file_bytes(path) : std::string()}});
  });
  s.server.Post("/api/check", [&s](const httplib::Request& req, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(s.work);
    try {
      reply_json(res, 200, verdict_of(s.built_for(req.body)));
    } catch (const InputError& e) {
      reply_json(res, 200, verdict_of(e));
    }
  });
  s.server.Post("/api/model.png", [&s](const httplib::Request& req, httplib::Response& res) {
    s.handle(req, res, [&](const Built& b) {
      res.set_content(s.renderers.model_png(b.model), "image/png");
    });
  });
  s.server.Post("/api/model.glb", [&s](const httplib::Request& req, httplib::Response& res) {
    s.handle(req, res, [&](const Built& b) {
      res.set_content(model_to_glb(b.model, GltfModelOptions{}), "model/gltf-binary");
    });
  });
  s.server.Post("/api/section.png", [&s](const httplib::Request& req, httplib::Response& res) {
    s.handle(req, res, [&](const Built& b) {
      const Outcome<double> y = parse_decimal(req.get_param_value("y"), "y");
      if (!y) {
        reply_json(res, 400, {{"ok", false}, {"message", y.reason() + " (template units)"}});
        return;
      }
      Plane plane;
      plane.point = {0, *y * b.tmpl.metres_per_unit, 0};
      plane.normal = {0, 1, 0};
      // While the plane is dragged the page asks for coarse cuts, then a full one.
      const bool coarse = req.get_param_value("coarse") == "1";
      std::unique_ptr<DiffusionBackend>& backend =
          coarse ? s.coarse_section_backend : s.section_backend;
      if (!backend)
        backend = make_cpu_diffusion(
            b.model, {coarse ? s.options.coarse_section_cube : s.options.section_cube, 0});
      CrossSectionOptions o;
      o.edge_m = b.tmpl.edge_m;
      const Outcome<CrossSection> section =
          make_cross_section(b.model, plane, *backend, o);
      if (!section) {
        reply_json(res, 422, {{"ok", false}, {"message", section.reason()}});
        return;
      }
      res.set_content(s.renderers.section_png(*section), "image/png");
    });
  });
  // A strip of seeded variants (seeds 1..count, count 1..8, default 4): their mid-height cuts,
  // as `cutaway variants` draws its contact sheet. It takes seconds, so it holds the library
  // only to get the template and to draw: checks and cuts of newer text go on meanwhile.
  s.server.Post("/api/variants.png", [&s](const httplib::Request& req, httplib::Response& res) {
    const std::string given = req.has_param("count") ? req.get_param_value("count") : "4";
    const int count = given.size() == 1 && given[0] >= '1' && given[0] <= '8' ? given[0] - '0' : 0;
    if (count == 0) {
      reply_json(res, 400, {{"ok", false}, {"message", "count must be a whole number from 1 to 8"}});
      return;
    }
    std::optional<Template> tmpl;
    s.handle(req, res, [&](const Built& b) { tmpl = b.tmpl; });
    if (!tmpl) return;  // handle() answered with the verdict
    const int cube = s.options.variant_cube;
    const DiffusionFactory diffusion = [cube](const DsModel& m) {
      return make_cpu_diffusion(m, {cube, 0});
    };
    answer_or_refuse(res, [&] {
      std::vector<Outcome<CrossSection>> sections;
      for (int seed = 1; seed <= count; ++seed)
        sections.push_back(variant_section(make_variant(*tmpl, seed), diffusion));
      if (std::none_of(sections.begin(), sections.end(), [](const auto& c) { return bool(c); })) {
        reply_json(res, 422, {{"ok", false},
                              {"message", "no variant has a cut at mid-height: " + sections[0].reason()}});
        return;
      }
      const std::lock_guard<std::mutex> lock(s.work);  // the renderers are one at a time
      res.set_content(s.renderers.variants_png(std::move(sections)), "image/png");
    });
  });
  s.server.Post("/api/save", [&s](const httplib::Request& req, httplib::Response& res) {
    s.handle(req, res, [&](const Built&) {
      write_file_atomically(s.options.template_path, req.body);
      reply_json(res, 200, {{"ok", true}, {"file", s.options.template_path.filename().string()}});
    });
  });

  if (s.options.port == 0) {
    s.port = s.server.bind_to_any_port("127.0.0.1");
  } else if (s.server.bind_to_port("127.0.0.1", s.options.port)) {
    s.port = s.options.port;
  }
  if (s.port <= 0)
    throw std::runtime_error("port " + std::to_string(s.options.port) +
                             " on 127.0.0.1 is taken; pass another with --port");
}

EditServer::~EditServer() = default;

int EditServer::port() const { return impl_->port; }

void EditServer::run() {
  Impl& s = *impl_;
  {
    const std::lock_guard<std::mutex> lock(s.state);
    if (s.stop_requested) return;
    s.serving = true;
  }
  s.server.listen_after_bind();
  const std::lock_guard<std::mutex> lock(s.state);
  s.serving = false;
}

void EditServer::stop() {
  Impl& s = *impl_;
  // httplib's stop() does nothing before its loop runs: wait for the loop (or for run() to
  // return) so that a stop() right after run() started is not lost.
  for (;;) {
    {
      const std::lock_guard<std::mutex> lock(s.state);
      s.stop_requested = true;
      if (!s.serving) return;
    }
    if (s.server.is_running()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  s.server.stop();
}

}  // namespace cutaway
