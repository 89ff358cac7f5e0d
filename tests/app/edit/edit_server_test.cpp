// The template editor's server (app/edit/edit_server.h): its security rules, each with a request
// that breaks it; the parser's verdict with line, column, field and rule; the pictures; and
// saving: every shipped template opened and saved unchanged keeps its model bytes. Its bounds,
// each with the request or load that broke them before: bodies too large whatever their
// encoding, slow clients by the hundred beside variant strips, a FIFO in place of the
// template, a file name that is not UTF-8. Its work only for its own page: requests without the
// page's token, a foreign page's image, a wrong volume name, work over the queue's bound and
// stale requests of a view start nothing, and checks are answered while work runs. Work is
// asserted by the server's counts and statuses, never by times.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/edit/edit_server.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// How long a wait for the server lasts before the test gives up on it: far past any work
/// here, so that a broken server fails its test instead of holding it. A guard against a hang,
/// never a measure: what the tests assert is counts, statuses and the order of events.
constexpr auto kHangGuard = 60s;

/// A server on a free port for `template_path`, running on its own thread while in scope, with
/// options as `adjust` makes them. Its pictures are stand-ins that say what they were given
/// (the OpenGL previews have tests of their own), or as `draw` makes them.
class RunningServer {
 public:
  explicit RunningServer(const fs::path& template_path,
                         const std::function<void(EditServerOptions&)>& adjust = nullptr,
                         const std::function<void(EditRenderers&)>& draw = nullptr) {
    EditServerOptions o;
    o.template_path = template_path;
    o.port = 0;
    o.max_body_bytes = 1u << 20;
    o.section_cube = 4;
    if (adjust) adjust(o);
    EditRenderers r;
    r.model_png = [](const DsModel& m) { return "model:" + std::to_string(m.surfaces.size()); };
    r.section_png = [](const CrossSection& s) {
      return "section:" + std::to_string(s.position.size());
    };
    r.variants_png = [](std::vector<Outcome<CrossSection>> cuts) {
      std::string out = "variants:";
      for (const auto& c : cuts) out += c ? std::to_string(c->position.size()) + "," : "-,";
      return out;
    };
    if (draw) draw(r);
    server_ = std::make_unique<EditServer>(o, r);
    thread_ = std::thread([this] { server_->run(); });
  }
  ~RunningServer() {
    server_->stop();
    thread_.join();
  }
  int port() const { return server_->port(); }
  const std::string& token() const { return server_->token(); }
  EditWorkCounts counts() const { return server_->work_counts(); }
  std::optional<std::string> cutting_page_url() const { return server_->cutting_page_url(); }
  /// A client that sends the server's own Host header and its page's token.
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port());
    c.set_read_timeout(std::chrono::duration_cast<std::chrono::seconds>(kHangGuard).count(), 0);
    c.set_default_headers({{std::string(kTokenHeader), token()}});
    return c;
  }

 private:
  std::unique_ptr<EditServer> server_;
  std::thread thread_;
};

fs::path copy_template(const std::string& name, const fs::path& dir) {
  const fs::path to = dir / (name + ".yaml");
  fs::copy_file(test::source_path("templates/" + name + ".yaml"), to);
  return to;
}

/// Whether `file` (a copy of the shipped tomato) still holds the shipped bytes.
bool untouched(const fs::path& file) {
  return test::read_file(file) == test::read_file(test::source_path("templates/tomato.yaml"));
}

/// The HTTP status of a request's answer, or -1 when no answer came.
int status_of(const httplib::Result& r) { return r ? r->status : -1; }

/// A TCP connection to the server made by hand, for requests no HTTP client sends: slow,
/// chunked, compressed. Closed when it goes out of scope.
class RawConnection {
 public:
  /// Connects to 127.0.0.1:`port`; reads and writes wait at most `timeout`.
  explicit RawConnection(int port, std::chrono::milliseconds timeout = kHangGuard)
      : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || ::connect(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0)
      ADD_FAILURE() << "cannot connect to port " << port << ": " << std::strerror(errno);
    const timeval tv{static_cast<time_t>(timeout.count() / 1000),
                     static_cast<suseconds_t>(timeout.count() % 1000 * 1000)};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    ::setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  }
  RawConnection(RawConnection&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }

  /// Sends all of `bytes`; false when the server closed the connection or stopped reading.
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      bytes.remove_prefix(static_cast<size_t>(n));
    }
    return true;
  }
  /// Whether the server holds the connection open now: nothing sent on it and not closed,
  /// looked at without waiting.
  bool still_open() {
    char c;
    const ssize_t n = ::recv(fd_, &c, 1, MSG_PEEK | MSG_DONTWAIT);
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
  /// What the server sends until it closes the connection; "...<still open>" when the read
  /// timeout passed first.
  std::string read_to_close() {
    std::string got;
    std::array<char, 4096> buffer;
    for (;;) {
      const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
      if (n > 0) {
        got.append(buffer.data(), static_cast<size_t>(n));
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) got += "<still open>";
      return got;
    }
  }

 private:
  int fd_;
};

/// The status of an HTTP answer read raw, or -1 when there is none.
int raw_status(const std::string& answer) {
  return answer.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(answer.c_str() + 9) : -1;
}

/// A request head for `server`, with its Host and token and `headers` (each ending in CRLF).
std::string request_head(const RunningServer& server, const std::string& line,
                         const std::string& headers) {
  return line + "\r\nHost: 127.0.0.1:" + std::to_string(server.port()) + "\r\n" +
         std::string(kTokenHeader) + ": " + server.token() + "\r\n" + headers + "\r\n";
}

TEST(EditServer, RefusesForeignHostsAndOrigins) {
  EXPECT_TRUE(check_request("127.0.0.1:8765", "", 8765));
  EXPECT_TRUE(check_request("localhost:8765", "http://localhost:8765", 8765));
  EXPECT_FALSE(check_request("evil.example:8765", "", 8765));  // DNS rebinding
  EXPECT_FALSE(check_request("127.0.0.1:9999", "", 8765));     // another port
  EXPECT_FALSE(check_request("", "", 8765));                   // no Host at all
  EXPECT_FALSE(check_request("127.0.0.1:8765", "http://evil.example", 8765));
  EXPECT_FALSE(check_request("127.0.0.1:8765", "https://127.0.0.1:8765", 8765));

  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file);
  httplib::Client c = server.client();
  EXPECT_EQ(status_of(c.Get("/api/template")), 200);
  const auto rebound =
      c.Get("/api/template", {{"Host", "evil.example:" + std::to_string(server.port())}});
  EXPECT_EQ(status_of(rebound), 403);
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->body.find("tomato"), std::string::npos);  // nothing of the template leaks
  EXPECT_EQ(
      status_of(c.Post("/api/save", {{"Origin", "http://evil.example"}}, "name: x", "text/plain")),
      403);
  EXPECT_TRUE(untouched(file));
}

TEST(EditServer, ServesOnlyItsOwnPageAndTemplate) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file);
  httplib::Client c = server.client();
  const auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("editor.js"), std::string::npos);
  for (const char* path : {"/editor.js", "/editor.css"})
    EXPECT_EQ(status_of(c.Get(path)), 200) << path;
  for (const char* path : {"/../tomato.yaml", "/tomato.yaml", "/%2e%2e/%2e%2e/etc/passwd",
                           "/api/template/../../etc/passwd", "/index.html/..", "/web/editor.js"})
    EXPECT_EQ(status_of(c.Get(path)), 404) << path;
  const auto t = c.Get("/api/template?file=../../etc/passwd");  // parameters name nothing
  ASSERT_TRUE(t);
  EXPECT_EQ(nlohmann::json::parse(t->body)["file"], "tomato.yaml");
}

// The page's libraries come from their own folders, and no request reaches past them.
TEST(EditServer, ServesLibrariesOnlyFromTheirFolders) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path lib = dir / "lib" / "dist";
  fs::create_directories(lib / "sub");
  std::ofstream(lib / "index.js") << "export const x = 1;";
  std::ofstream(lib / "sub" / "part.js") << "export const y = 2;";
  std::ofstream(lib / ".hidden.js") << "secret";
  std::ofstream(lib / "notes.txt") << "secret";
  std::ofstream(dir / "lib" / "outside.js") << "secret";
  fs::create_symlink(dir / "lib" / "outside.js", lib / "link.js");  // leads out of the folder
  EXPECT_EQ(library_file(lib, "index.js"), fs::canonical(lib / "index.js"));
  EXPECT_EQ(library_file(lib, "sub/part.js"), fs::canonical(lib / "sub" / "part.js"));
  for (const char* bad :
       {"../outside.js", "sub/../../outside.js", "./index.js", ".hidden.js", "notes.txt", "link.js",
        "sub//part.js", "/etc/passwd.js", "sub", "missing.js", "a b.js", "sub/", ""})
    EXPECT_FALSE(library_file(lib, bad)) << bad;

  const fs::path file = copy_template("tomato", dir);
  EditServerOptions o;
  o.template_path = file;
  o.port = 0;
  o.libraries = {{"yaml", lib}};
  EditServer server(o, EditRenderers{});
  std::thread serving([&] { server.run(); });
  httplib::Client c("127.0.0.1", server.port());
  const auto got = c.Get("/lib/yaml/sub/part.js");
  ASSERT_TRUE(got);
  EXPECT_EQ(got->status, 200);
  EXPECT_EQ(got->body, "export const y = 2;");
  for (const char* path :
       {"/lib/yaml/../outside.js", "/lib/yaml/%2e%2e/outside.js", "/lib/yaml/link.js",
        "/lib/yaml/notes.txt", "/lib/three/index.js", "/lib/yaml/..%2foutside.js"})
    EXPECT_EQ(status_of(c.Get(path)), 404) << path;
  server.stop();
  serving.join();
}

TEST(EditServer, RefusesOversizedBodies) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file, [](EditServerOptions& o) { o.max_body_bytes = 1000; });
  httplib::Client c = server.client();
  EXPECT_EQ(status_of(c.Post("/api/save", std::string(5000, '#'), "text/plain")), 413);
  EXPECT_TRUE(untouched(file));
}

TEST(EditServer, SaysWhereTheTextBreaksARule) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  std::string text = test::read_file(file);
  const nlohmann::json good = check_template_text(text, file);
  ASSERT_TRUE(good["ok"]) << good.dump();
  EXPECT_EQ(good["surfaces"], build_model(load_template(file.string())).surfaces.size());
  EXPECT_LT(good["bbox_min"][1].get<double>(), good["bbox_max"][1].get<double>());
  // The curves as fitted, in template units: the skin's profile runs from its first point
  // (0, 3) to its last (0, 50) through more samples than points; the core's section is a circle
  // (none given), the chambers have one loop per fold.
  const nlohmann::json& curves = good["curves"];
  ASSERT_EQ(curves.size(), 4u);
  const nlohmann::json& skin = curves[0]["profile"];
  EXPECT_GT(skin.size(), 10u);
  EXPECT_NEAR(skin.front()[1].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(skin.back()[1].get<double>(), 50.0, 1e-9);
  EXPECT_EQ(curves[2]["sections"].size(), 5u);
  EXPECT_TRUE(curves[3]["sections"].empty());
  const size_t at = text.find("units: mm");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 9, "units: furlongs");
  const nlohmann::json bad = check_template_text(text, file);
  EXPECT_FALSE(bad["ok"]);
  EXPECT_EQ(bad["file"], "tomato.yaml");
  EXPECT_EQ(bad["field"], "units");
  EXPECT_EQ(bad["line"].get<int>(),
            1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')));
  EXPECT_GE(bad["column"].get<int>(), 1);
  EXPECT_NE(bad["rule"].get<std::string>(), "");
  // Over HTTP: the same verdict; pictures and saving refuse the text with it (422), and the
  // file on disk stays as it was.
  RunningServer server(file);
  httplib::Client c = server.client();
  const auto checked = c.Post("/api/check", text, "text/plain");
  ASSERT_TRUE(checked);
  EXPECT_EQ(nlohmann::json::parse(checked->body), bad);
  for (const char* path : {"/api/model.png", "/api/section.png?y=30", "/api/save"}) {
    const auto r = c.Post(path, text, "text/plain");
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 422) << path;
    EXPECT_EQ(nlohmann::json::parse(r->body)["field"], "units") << path;
  }
  EXPECT_TRUE(untouched(file));
}

TEST(EditServer, DrawsTheModelAndACutAtAHeight) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file);
  RunningServer server(file);
  httplib::Client c = server.client();
  const auto model = c.Post("/api/model.png", text, "text/plain");
  ASSERT_TRUE(model);
  EXPECT_EQ(model->status, 200);
  EXPECT_EQ(model->body,
            "model:" + std::to_string(build_model(load_template(file.string())).surfaces.size()));
  const auto cut = c.Post("/api/section.png?y=26", text, "text/plain");
  ASSERT_TRUE(cut);
  EXPECT_EQ(cut->status, 200);
  EXPECT_EQ(cut->body.rfind("section:", 0), 0u);
  EXPECT_NE(cut->body, "section:0");
  const auto coarse = c.Post("/api/section.png?y=26&coarse=1", text, "text/plain");
  ASSERT_TRUE(coarse);
  EXPECT_EQ(coarse->status, 200);
  EXPECT_NE(coarse->body, "section:0");
  EXPECT_EQ(status_of(c.Post("/api/section.png?y=5000", text, "text/plain")), 422);  // misses
  EXPECT_EQ(status_of(c.Post("/api/section.png?y=up", text, "text/plain")), 400);
  // The variants' strip: four cuts (seeds 1..4), each a real section; a bad count is refused.
  const auto variants = c.Post("/api/variants.png", text, "text/plain");
  ASSERT_TRUE(variants);
  EXPECT_EQ(variants->status, 200);
  EXPECT_EQ(std::count(variants->body.begin(), variants->body.end(), ','), 4);
  EXPECT_EQ(variants->body.find("-,"), std::string::npos) << variants->body;
  EXPECT_EQ(status_of(c.Post("/api/variants.png?count=9", text, "text/plain")), 400);
  // The 3D view's model: the same bytes as `cutaway model` writes.
  const auto glb = c.Post("/api/model.glb", text, "text/plain");
  ASSERT_TRUE(glb);
  EXPECT_EQ(glb->status, 200);
  EXPECT_EQ(glb->body, model_to_glb(build_model(load_template(file.string())), GltfModelOptions{}));
}

TEST(EditServer, ShowsTheOutsideWithTheSkinsPatternsAndRelief) {
  // The cantaloupe's skin: a net with a relief. The outside is one textured, normal-mapped
  // skin with the camera, the studio lights and the exposure scenes have, a valid glTF; a text
  // that breaks a rule gets the verdict.
  const fs::path dir = test::fresh_dir("edit-outside");
  const fs::path file = copy_template("cantaloupe", dir);
  const std::string text = test::read_file(file);
  RunningServer server(file);
  httplib::Client c = server.client();
  const auto skin = c.Post("/api/skin.glb", text, "text/plain");
  ASSERT_TRUE(skin);
  ASSERT_EQ(skin->status, 200);
  EXPECT_EQ(skin->get_header_value("Content-Type"), "model/gltf-binary");
  const fs::path glb = dir / "outside.glb";
  std::ofstream(glb, std::ios::binary) << skin->body;
  const test::GltfReport report = test::validate_gltf(glb);
  EXPECT_EQ(report.errors, 0) << report.output;
  uint32_t length = 0;
  std::memcpy(&length, skin->body.data() + 12, 4);
  const nlohmann::json gltf = nlohmann::json::parse(skin->body.substr(20, length));
  EXPECT_EQ(gltf["cameras"].size(), 1u);
  EXPECT_EQ(gltf["extensions"]["KHR_lights_punctual"]["lights"].size(), 3u);  // key, fill, rim
  EXPECT_TRUE(gltf["scenes"][0]["extras"].contains("exposure"));
  EXPECT_TRUE(gltf["scenes"][0]["extras"].contains("ambient_lux"));
  size_t relief = 0;
  for (const auto& material : gltf["materials"])
    relief += material.contains("normalTexture") &&
              material["pbrMetallicRoughness"].contains("baseColorTexture");
  EXPECT_EQ(relief, 1u);
  std::string broken = text;
  broken.replace(broken.find("units: mm"), 9, "units: furlongs");
  EXPECT_EQ(status_of(c.Post("/api/skin.glb", broken, "text/plain")), 422);
}

// Every shipped template, opened and saved unchanged through the server, builds the same model
// bytes; a new template (no file yet) can be saved, and a saved edit is what is on disk.
TEST(EditServer, OpeningAndSavingEveryShippedTemplateKeepsItsModel) {
  const fs::path dir = test::fresh_dir("edit");
  // The whole folder: `mesh` surfaces name their PLY files beside the template.
  fs::copy(test::source_path("templates"), dir);
  for (const auto& entry : fs::directory_iterator(test::source_path("templates"))) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const fs::path file = dir / entry.path().filename();
    const std::string before = model_to_glb(build_model(load_template(file.string())), {});
    RunningServer server(file);
    httplib::Client c = server.client();
    const auto opened = c.Get("/api/template");
    ASSERT_TRUE(opened);
    const nlohmann::json doc = nlohmann::json::parse(opened->body);
    ASSERT_TRUE(doc["exists"]);
    const auto saved = c.Post("/api/save", doc["text"].get<std::string>(), "text/plain");
    ASSERT_TRUE(saved);
    ASSERT_EQ(saved->status, 200) << saved->body;
    EXPECT_EQ(test::read_file(file), test::read_file(entry.path()));
    EXPECT_EQ(model_to_glb(build_model(load_template(file.string())), {}), before);
  }
  const fs::path fresh = dir / "new-fruit.yaml";
  RunningServer server(fresh);
  httplib::Client c = server.client();
  const auto opened = c.Get("/api/template");
  ASSERT_TRUE(opened);
  EXPECT_FALSE(nlohmann::json::parse(opened->body)["exists"]);
  std::string text = test::read_file(test::source_path("templates/tomato.yaml"));
  text.replace(text.find("name: tomato"), 12, "name: new-fruit");
  const auto saved = c.Post("/api/save", text, "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 200) << saved->body;
  EXPECT_EQ(test::read_file(fresh), text);
}

TEST(EditServer, ATakenPortIsAClearError) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer first(file);
  EditServerOptions o;
  o.template_path = file;
  o.port = first.port();
  try {
    EditServer second(o, EditRenderers{});
    ADD_FAILURE() << "a second server bound the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is taken; pass another with --port"), std::string::npos)
        << e.what();
  }
}

// A chunked body is bounded as one with a Content-Length: past the limit the server answers 413
// and stops reading (600 MB were once taken in); a small chunked body is served.
TEST(EditServer, BoundsChunkedBodies) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  constexpr size_t kLimit = 64u << 10;
  RunningServer server(file, [](EditServerOptions& o) { o.max_body_bytes = kLimit; });
  RawConnection big(server.port());
  ASSERT_TRUE(
      big.send(request_head(server, "POST /api/check HTTP/1.1", "Transfer-Encoding: chunked\r\n")));
  // A sender offers 256 MiB in 64 KiB chunks; the server's answer must come long before.
  std::atomic<size_t> sent{0};
  std::thread sender([&] {
    const std::string chunk = "10000\r\n" + std::string(0x10000, 'a') + "\r\n";
    for (int k = 0; k < 4096 && big.send(chunk); ++k) sent += chunk.size();
  });
  const std::string answer = big.read_to_close();
  sender.join();
  EXPECT_EQ(raw_status(answer), 413) << answer.substr(0, 300);
  EXPECT_NE(answer.find("limited to 65536 bytes"), std::string::npos) << answer.substr(0, 300);
  EXPECT_LT(sent.load(), size_t{64} << 20);  // the server stopped reading near the limit

  const std::string text = "format: cutaway-template/1\nname: x\n";
  RawConnection small(server.port());
  ASSERT_TRUE(small.send(request_head(server, "POST /api/check HTTP/1.1",
                                      "Transfer-Encoding: chunked\r\nConnection: close\r\n")));
  char size[16];
  std::snprintf(size, sizeof size, "%zx\r\n", text.size());
  ASSERT_TRUE(small.send(size + text + "\r\n0\r\n\r\n"));
  const std::string verdict = small.read_to_close();
  EXPECT_EQ(raw_status(verdict), 200) << verdict;
  EXPECT_NE(verdict.find("\"ok\":false"), std::string::npos) << verdict;  // read, then checked
}

// Bodies the page never sends are refused from their head, before any of them is read:
// compressed ones (a 305 KB gzip body once inflated to 300 MiB), POSTs without a length, other
// methods; the connection closes after the answer.
TEST(EditServer, RefusesBodiesItCannotBound) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file);
  const auto answer = [&](const std::string& line, const std::string& headers,
                          const std::string& body) {
    RawConnection c(server.port());
    c.send(request_head(server, line, headers) + body);
    return c.read_to_close();
  };
  const std::string gzip_bytes("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03", 10);
  EXPECT_EQ(raw_status(answer("POST /api/check HTTP/1.1",
                              "Content-Encoding: gzip\r\nContent-Length: 10\r\n", gzip_bytes)),
            415);
  EXPECT_EQ(raw_status(answer("POST /api/save HTTP/1.1",
                              "Content-Encoding: br\r\nContent-Length: 10\r\n", gzip_bytes)),
            415);
  EXPECT_EQ(raw_status(answer("POST /api/check HTTP/1.1", "Transfer-Encoding: gzip, chunked\r\n",
                              "a\r\n" + gzip_bytes)),
            415);
  EXPECT_EQ(raw_status(answer("POST /api/check HTTP/1.1", "", "name: x")), 411);
  EXPECT_EQ(raw_status(answer("POST /api/check HTTP/1.1", "Content-Length: 12x\r\n", "")), 400);
  EXPECT_EQ(raw_status(answer("PUT /api/save HTTP/1.1", "Content-Length: 7\r\n", "name: x")), 405);
  EXPECT_EQ(raw_status(answer("GET / HTTP/1.1", "Content-Length: 7\r\n", "name: x")), 400);
  const std::string over =
      answer("POST /api/save HTTP/1.1", "Content-Length: 999999999999\r\n", "");
  EXPECT_EQ(raw_status(over), 413) << over;
  // The answer says it closes the connection, once, whether or not the client asked to.
  const auto closes = [](const std::string& a) {
    const std::string head = a.substr(0, a.find("\r\n\r\n"));
    size_t n = 0;
    for (size_t at = head.find("Connection: close"); at != std::string::npos;
         at = head.find("Connection: close", at + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(closes(over), 1u) << over;
  const std::string asked =
      answer("POST /api/check HTTP/1.1",
             "Content-Encoding: gzip\r\nContent-Length: 10\r\nConnection: close\r\n", gzip_bytes);
  EXPECT_EQ(raw_status(asked), 415) << asked;
  EXPECT_EQ(closes(asked), 1u) << asked;
  EXPECT_TRUE(untouched(file));
}

// 200 clients that send their heads a line at a time (slowloris) and eight strips of variants
// at once do not delay checks: the checks are answered while the slow connections are still
// held and while a strip is being made, the slow connections are closed at the request timeout,
// and only one strip is made at a time (the older requests are answered 409). The test orders
// events rather than timing them: a strip makes eight variants and cuts them, a check builds one
// model, so a check queued behind a strip or a slow client would be answered after it.
TEST(EditServer, AnswersChecksBesideSlowClientsAndVariants) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file);
  constexpr auto kTimeout = 10s;  // long past the checks, even on a loaded machine
  RunningServer server(file, [&](EditServerOptions& o) {
    o.request_timeout = kTimeout;
    o.variant_cube = 4;
  });
  const int port = server.port();

  std::vector<RawConnection> slow;
  for (int k = 0; k < 200; ++k) {
    slow.emplace_back(port, kTimeout + 5s);
    ASSERT_TRUE(
        slow.back().send("GET / HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n"));
  }
  std::vector<int> variants_status(8, 0);
  std::vector<Clock::time_point> variants_answered(8);
  std::vector<std::thread> variants;
  for (size_t k = 0; k < variants_status.size(); ++k) {
    variants.emplace_back([&, k] {
      httplib::Client c = server.client();
      variants_status[k] = status_of(c.Post("/api/variants.png?count=8", text, "text/plain"));
      variants_answered[k] = Clock::now();
    });
  }
  httplib::Client c = server.client();
  std::vector<Clock::time_point> checks_answered;
  for (int k = 0; k < 5; ++k) {
    // New text each time, as the page sends: each check builds its model.
    const std::string edited = text + "# edit " + std::to_string(k) + "\n";
    const auto checked = c.Post("/api/check", edited, "text/plain");
    checks_answered.push_back(Clock::now());
    ASSERT_TRUE(checked) << "check " << k;
    EXPECT_EQ(checked->status, 200);
    EXPECT_TRUE(nlohmann::json::parse(checked->body)["ok"]) << checked->body;
    for (RawConnection& s : slow) s.send("X-Slow: " + std::to_string(k) + "\r\n");
    std::this_thread::sleep_for(20ms);
  }
  // The checks were answered while the slow connections were held: every one is still open
  // after the last check. Then the server closes each of them at its request timeout.
  const auto open_after_checks =
      std::count_if(slow.begin(), slow.end(), [](RawConnection& s) { return s.still_open(); });
  EXPECT_EQ(open_after_checks, static_cast<long>(slow.size()))
      << "the checks waited for slow clients";
  for (RawConnection& s : slow) {
    const std::string got = s.read_to_close();
    if (got.find("<still open>") != std::string::npos) {
      ADD_FAILURE() << "a slow connection is still open: " << got;
      break;
    }
  }
  for (std::thread& t : variants) t.join();
  // A strip was made, and every check was answered before it was.
  for (const int status : variants_status) EXPECT_TRUE(status == 200 || status == 409) << status;
  Clock::time_point strip_made = Clock::time_point::min();
  for (size_t k = 0; k < variants_status.size(); ++k)
    if (variants_status[k] == 200) strip_made = std::max(strip_made, variants_answered[k]);
  ASSERT_NE(strip_made, Clock::time_point::min()) << "no strip was made";
  EXPECT_TRUE(checks_answered.back() < strip_made) << "the strip was made before the last check";
}

// Connections over the bound are answered 503 at once; once one closes, another is served (the
// server sees the close a moment later: until then a request is still turned away, 503).
TEST(EditServer, TurnsAwayConnectionsOverTheBound) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file, [](EditServerOptions& o) { o.max_connections = 3; });
  std::vector<RawConnection> held;
  for (int k = 0; k < 3; ++k) held.emplace_back(server.port());
  RawConnection over(server.port());
  over.send(request_head(server, "GET /api/template HTTP/1.1", ""));
  const std::string refused = over.read_to_close();
  EXPECT_EQ(raw_status(refused), 503) << refused;
  held.pop_back();
  int status = 503;
  for (const Clock::time_point until = Clock::now() + kHangGuard;
       status == 503 && Clock::now() < until;) {
    std::this_thread::sleep_for(50ms);
    status = status_of(server.client().Get("/api/template"));
  }
  EXPECT_EQ(status, 200);
}

// A FIFO in place of the template is refused at once, without opening it for a blocking read
// (it once hung every request behind it); other requests go on, and saving does not write
// through it.
TEST(EditServer, RefusesATemplateThatIsNotARegularFile) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path fifo = dir / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string text = test::read_file(test::source_path("templates/tomato.yaml"));
  RunningServer server(fifo);
  httplib::Client c = server.client();
  const auto opened = c.Get("/api/template");
  ASSERT_TRUE(opened);
  EXPECT_EQ(opened->status, 500);
  const nlohmann::json refusal = nlohmann::json::parse(opened->body);
  EXPECT_NE(refusal["message"].get<std::string>().find("not a regular file"), std::string::npos)
      << opened->body;
  EXPECT_EQ(status_of(c.Post("/api/check", text, "text/plain")), 200);
  const auto saved = c.Post("/api/save", text, "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 500) << saved->body;
  EXPECT_NE(saved->body.find("not a regular file"), std::string::npos) << saved->body;
  EXPECT_TRUE(fs::is_fifo(fifo));
}

/// `cutaway edit TEMPLATE --port 0` started in the background, its output in `log`.
pid_t start_editor(const fs::path& template_path, const fs::path& log) {
  std::vector<std::string> words{CUTAWAY_BINARY, "edit", template_path.string(), "--port", "0"};
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string log_path = log.string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const int out = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_RDONLY);
    ::dup2(null, 0);
    ::dup2(out, 1);
    ::dup2(out, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

/// The port the editor `pid` printed in `log`, waiting until it does; 0 when it ended first
/// (not reaped) or kHangGuard passed.
int printed_port(pid_t pid, const fs::path& log) {
  const std::regex address(R"(127\.0\.0\.1:(\d+)/)");
  for (const Clock::time_point until = Clock::now() + kHangGuard; Clock::now() < until;) {
    std::smatch m;
    const std::string text = test::read_file(log);
    if (std::regex_search(text, m, address)) return std::stoi(m[1]);
    siginfo_t ended{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &ended, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        ended.si_pid == pid)
      return 0;
    std::this_thread::sleep_for(20ms);
  }
  return 0;
}

/// The token in the page that the server `c` talks to serves at /; empty when there is none.
std::string token_of_page(httplib::Client& c) {
  const auto page = c.Get("/");
  std::smatch m;
  const std::regex meta(R"re(<meta name="cutaway-token" content="([0-9a-f]{32})">)re");
  return page && std::regex_search(page->body, m, meta) ? m[1].str() : "";
}

/// Whether the child `pid` ended within kHangGuard, its wait status in *status (reaped).
bool ends(pid_t pid, int* status) {
  for (const Clock::time_point until = Clock::now() + kHangGuard; Clock::now() < until;) {
    if (::waitpid(pid, status, WNOHANG) == pid) return true;
    std::this_thread::sleep_for(20ms);
  }
  return false;
}

// The command with a FIFO for its template: the page's first request is answered (an error)
// without a read of the FIFO, and SIGTERM stops the process (once it could not), even while a
// slow client holds a connection.
TEST(EditServer, StopsOnSigtermWithAFifoTemplate) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path fifo = dir / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path log = dir / "edit.log";
  const pid_t pid = start_editor(fifo, log);
  ASSERT_GT(pid, 0);
  const int port = printed_port(pid, log);
  int status = 0;
  if (port == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL() << "no address printed:\n" << test::read_file(log);
  }
  httplib::Client c("127.0.0.1", port);
  c.set_read_timeout(std::chrono::duration_cast<std::chrono::seconds>(kHangGuard).count(), 0);
  c.set_default_headers({{std::string(kTokenHeader), token_of_page(c)}});
  EXPECT_EQ(status_of(c.Get("/api/template")), 500);
  RawConnection slow(port);
  slow.send("GET / HTTP/1.1\r\n");
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  const bool ended = ends(pid, &status);
  if (!ended) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  EXPECT_TRUE(ended) << test::read_file(log);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status << test::read_file(log);
}

// A template file whose name is not UTF-8: every answer is JSON (the byte becomes U+FFFD),
// where it once was a 500 with an empty body; saving answers 200 and writes the text once.
TEST(EditServer, ServesAFileNameThatIsNotUtf8) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = dir / "tom\xff"
                              "ato.yaml";
  fs::copy_file(test::source_path("templates/tomato.yaml"), file);
  RunningServer server(file);
  httplib::Client c = server.client();
  const auto opened = c.Get("/api/template");
  ASSERT_TRUE(opened);
  ASSERT_EQ(opened->status, 200) << opened->body;
  const nlohmann::json doc = nlohmann::json::parse(opened->body);
  EXPECT_EQ(doc["file"], "tom\xef\xbf\xbd"
                         "ato.yaml");
  std::string text = doc["text"].get<std::string>();
  const auto bad = c.Post("/api/check", "units: furlongs\n", "text/plain");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 200);
  EXPECT_EQ(nlohmann::json::parse(bad->body)["file"], "tom\xef\xbf\xbd"
                                                      "ato.yaml");
  text += "# saved\n";
  const auto saved = c.Post("/api/save", text, "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 200) << saved->body;
  EXPECT_TRUE(nlohmann::json::parse(saved->body)["ok"]);
  EXPECT_EQ(test::read_file(file), text);
}

// A save that cannot be written answers an error and leaves what was there.
TEST(EditServer, ASaveThatFailsWritesNothing) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path folder = dir / "folder.yaml";  // a folder where the template should be
  fs::create_directory(folder);
  const std::string text = test::read_file(test::source_path("templates/tomato.yaml"));
  RunningServer server(folder);
  const auto saved = server.client().Post("/api/save", text, "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 500);
  EXPECT_NE(nlohmann::json::parse(saved->body)["message"].get<std::string>().find("is a directory"),
            std::string::npos)
      << saved->body;
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_TRUE(fs::is_empty(folder));
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{});
}

/// Waits until `server`'s work counts pass `ready` (at most kHangGuard, for a broken server);
/// whether they did.
bool counts_reach(const RunningServer& server,
                  const std::function<bool(const EditWorkCounts&)>& ready) {
  for (const Clock::time_point until = Clock::now() + kHangGuard; Clock::now() < until;) {
    if (ready(server.counts())) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

/// Where stand-in pictures wait until the test opens it, so that work stays running for as
/// long as the test needs.
class Gate {
 public:
  /// Called by a picture: counts it in, then waits until the gate is open.
  void pass() {
    std::unique_lock<std::mutex> lock(mutex_);
    ++arrived_;
    changed_.notify_all();
    changed_.wait(lock, [&] { return open_; });
  }
  /// Waits until `n` pictures have arrived (at most kHangGuard); whether they did.
  bool arrived(int n) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, kHangGuard, [&] { return arrived_ >= n; });
  }
  void open() {
    const std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int arrived_ = 0;
  bool open_ = false;
};

// Every request to /api/ needs the token of the page the server served, a new one for each
// server: without it, or with another server's, it is refused (403) before any work, and the
// file is not written. The pages carry it and are not cached.
TEST(EditServer, RefusesApiRequestsWithoutThePagesToken) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file) + "# edited\n";
  RunningServer server(file, [](EditServerOptions& o) { o.volume_voxels_across = 8; });
  RunningServer other(file);
  EXPECT_EQ(server.token().size(), 32u);
  EXPECT_NE(server.token(), other.token());
  httplib::Client c("127.0.0.1", server.port());  // a client without the token
  EXPECT_EQ(token_of_page(c), server.token());
  const auto cutting = c.Get("/cut.html");
  ASSERT_TRUE(cutting);
  EXPECT_NE(cutting->body.find("content=\"" + server.token() + "\""), std::string::npos);
  EXPECT_EQ(cutting->get_header_value("Cache-Control"), "no-store");
  const std::string header(kTokenHeader);
  for (const char* path :
       {"/api/check", "/api/model.png", "/api/model.glb", "/api/skin.glb", "/api/section.png?y=26",
        "/api/variants.png", "/api/save", "/api/volume/tomato.json", "/api/volume/tomato.glb"}) {
    for (const httplib::Headers& headers :
         {httplib::Headers{}, httplib::Headers{{header, other.token()}},
          httplib::Headers{{header, ""}}, httplib::Headers{{header, server.token().substr(1)}}})
      EXPECT_EQ(status_of(c.Post(path, headers, text, "text/plain")), 403) << path;
  }
  EXPECT_EQ(status_of(c.Get("/api/template")), 403);
  const EditWorkCounts counts = server.counts();
  EXPECT_EQ(counts.finished + counts.running + counts.waiting, 0);
  EXPECT_EQ(counts.volumes_sampled, 0);
  EXPECT_TRUE(untouched(file));
  EXPECT_EQ(status_of(server.client().Post("/api/check", text, "text/plain")), 200);
}

// A page of another origin that embeds <img src="http://127.0.0.1:PORT/api/volume/x.json">
// makes the browser send a GET with the right Host and no Origin: it starts no work (it once
// sampled a volume for minutes). Nor does a GET with the token: the volume is POST only.
TEST(EditServer, AForeignPagesImageStartsNoWork) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file, [](EditServerOptions& o) { o.volume_voxels_across = 8; });
  const std::string port = std::to_string(server.port());
  for (const std::string& host : {"127.0.0.1:" + port, "localhost:" + port}) {
    for (const char* path :
         {"/api/volume/anything.json", "/api/volume/tomato.json", "/api/volume/tomato.glb"}) {
      RawConnection img(server.port());
      img.send(std::string("GET ") + path + " HTTP/1.1\r\nHost: " + host +
               "\r\nAccept: image/avif,image/webp,image/*,*/*;q=0.8\r\n"
               "Referer: http://127.0.0.1:1/page.html\r\nSec-Fetch-Site: same-site\r\n"
               "Sec-Fetch-Mode: no-cors\r\nSec-Fetch-Dest: image\r\nConnection: close\r\n\r\n");
      const std::string answer = img.read_to_close();
      EXPECT_EQ(raw_status(answer), 403) << host << path << answer;
    }
  }
  EXPECT_EQ(status_of(server.client().Get("/api/volume/tomato.json")), 404);
  const EditWorkCounts counts = server.counts();
  EXPECT_EQ(counts.volumes_sampled, 0);
  EXPECT_EQ(counts.finished + counts.running + counts.waiting, 0);
}

// The volume's name is compared before any work (a wrong one was once answered 404 after the
// whole volume was sampled); the volume is sampled once for its template, whichever files are
// asked for, and a save that changes only a comment does not sample it again.
// The address the edit command prints opens the cutting page of the saved template: the page,
// and the volume and model it names, are served; an unsaved template has none yet.
TEST(EditServer, TheCuttingPageUrlNamesTheSavedTemplate) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file, [](EditServerOptions& o) { o.volume_voxels_across = 8; });
  const std::string host = "http://127.0.0.1:" + std::to_string(server.port());
  const std::optional<std::string> url = server.cutting_page_url();
  ASSERT_TRUE(url);
  EXPECT_EQ(*url, host + "/cut.html?volume=/api/volume/tomato.json&model=/api/volume/tomato.glb");
  httplib::Client c = server.client();
  const auto page = c.Get(url->substr(host.size()));
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find(server.token()), std::string::npos);
  for (const char* named : {"/api/volume/tomato.json", "/api/volume/tomato.glb"})
    EXPECT_EQ(status_of(c.Post(named, "", "text/plain")), 200) << named;
  RunningServer unsaved(dir / "new-template.yaml");
  EXPECT_FALSE(unsaved.cutting_page_url());
}

TEST(EditServer, SamplesTheVolumeOnlyForItsNameAndOncePerTemplate) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file);
  RunningServer server(file, [](EditServerOptions& o) { o.volume_voxels_across = 8; });
  httplib::Client c = server.client();
  const auto wrong = c.Post("/api/volume/wrongname.json", "", "text/plain");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 404);
  EXPECT_NE(wrong->body.find("the volume of tomato"), std::string::npos) << wrong->body;
  EXPECT_EQ(server.counts().volumes_sampled, 0);
  EXPECT_EQ(server.counts().finished, 0);  // not even queued
  const auto sidecar = c.Post("/api/volume/tomato.json", "", "text/plain");
  ASSERT_TRUE(sidecar);
  ASSERT_EQ(sidecar->status, 200) << sidecar->body;
  EXPECT_EQ(nlohmann::json::parse(sidecar->body)["template"], "tomato");
  for (const char* kind : {"colour.png", "structure.png", "material.png", "glb"})
    EXPECT_EQ(status_of(c.Post(std::string("/api/volume/tomato.") + kind, "", "text/plain")), 200)
        << kind;
  EXPECT_EQ(server.counts().volumes_sampled, 1);
  EXPECT_EQ(status_of(c.Post("/api/save", text + "\n# only a comment\n", "text/plain")), 200);
  const auto again = c.Post("/api/volume/tomato.json", "", "text/plain");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->body, sidecar->body);
  EXPECT_EQ(server.counts().volumes_sampled, 1);
  // A change of the template (here its description) samples it again.
  std::string changed = text;
  changed.replace(changed.find("70 mm across"), 12, "71 mm across");
  EXPECT_EQ(status_of(c.Post("/api/save", changed, "text/plain")), 200);
  EXPECT_EQ(status_of(c.Post("/api/volume/tomato.json", "", "text/plain")), 200);
  EXPECT_EQ(server.counts().volumes_sampled, 2);
}

// Work is admitted up to max_work_requests, running or waiting; one more is refused at once
// with 503 and Retry-After, and checks and saves are answered while the work runs. A stand-in
// picture held at a gate keeps the work running for as long as the test needs.
TEST(EditServer, RefusesWorkOverItsBoundAndChecksMeanwhile) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file);
  Gate gate;
  RunningServer server(
      file,
      [](EditServerOptions& o) {
        o.max_work_requests = 2;
        o.volume_voxels_across = 8;
      },
      [&](EditRenderers& r) {
        r.model_png = [&](const DsModel&) {
          gate.pass();
          return std::string("model");
        };
      });
  int picture_status = 0, cut_status = 0;
  std::thread picture([&] {
    picture_status = status_of(server.client().Post("/api/model.png", text, "text/plain"));
  });
  ASSERT_TRUE(gate.arrived(1));
  // The cut runs beside it, then waits to draw (one picture at a time).
  std::thread cut([&] {
    cut_status = status_of(server.client().Post("/api/section.png?y=26", text, "text/plain"));
  });
  EXPECT_TRUE(counts_reach(server, [](const EditWorkCounts& c) { return c.running == 2; }));
  httplib::Client c = server.client();
  for (const char* path : {"/api/variants.png", "/api/skin.glb", "/api/volume/tomato.json"}) {
    const auto busy = c.Post(path, text, "text/plain");
    ASSERT_TRUE(busy) << path;
    EXPECT_EQ(busy->status, 503) << path;
    EXPECT_EQ(busy->get_header_value("Retry-After"), "1") << path;
  }
  const auto checked = c.Post("/api/check", text + "# edited\n", "text/plain");
  ASSERT_TRUE(checked);
  EXPECT_TRUE(nlohmann::json::parse(checked->body)["ok"]) << checked->body;
  EXPECT_EQ(status_of(c.Post("/api/save", text + "# saved\n", "text/plain")), 200);
  EditWorkCounts counts = server.counts();
  EXPECT_EQ(counts.running, 2);  // the check and the save were answered while both ran
  EXPECT_EQ(counts.finished, 0);
  EXPECT_EQ(counts.turned_away, 3);
  EXPECT_EQ(counts.volumes_sampled, 0);
  gate.open();
  picture.join();
  cut.join();
  EXPECT_EQ(picture_status, 200);
  EXPECT_EQ(cut_status, 200);
  counts = server.counts();
  EXPECT_EQ(counts.finished, 2);
  EXPECT_EQ(counts.running + counts.waiting, 0);
  EXPECT_EQ(status_of(c.Post("/api/variants.png?count=1", text, "text/plain")), 200);
}

// A newer request of a view replaces the older one waiting, which is answered 409 at once
// (before the running one ends); the one running finishes, then the newest runs.
TEST(EditServer, ANewerRequestOfAViewReplacesTheOlder) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  const std::string text = test::read_file(file);
  Gate gate;
  RunningServer server(file, nullptr, [&](EditRenderers& r) {
    r.model_png = [&](const DsModel&) {
      gate.pass();
      return std::string("model");
    };
  });
  std::array<int, 3> status{};
  const auto ask = [&](size_t k) {
    return std::thread([&, k] {
      status[k] = status_of(server.client().Post(
          "/api/model.png", text + "# edit " + std::to_string(k) + "\n", "text/plain"));
    });
  };
  std::thread first = ask(0);
  ASSERT_TRUE(gate.arrived(1));
  std::thread second = ask(1);
  EXPECT_TRUE(counts_reach(server, [](const EditWorkCounts& c) { return c.waiting == 1; }));
  std::thread third = ask(2);
  second.join();  // answered while the first is still held at the gate
  EXPECT_EQ(status[1], 409);
  EXPECT_EQ(server.counts().superseded, 1);
  EXPECT_EQ(server.counts().finished, 0);
  gate.open();
  first.join();
  third.join();
  EXPECT_EQ(status[0], 200);
  EXPECT_EQ(status[2], 200);
  EXPECT_EQ(server.counts().finished, 2);
}

// Twelve skin bakes asked for at once (the page once sent one per edit and cancelled none) held
// the one work lock, and a check waited behind them all. Now the check is answered while the
// first bake still runs, and the bakes do not pile up: one runs, one waits, the others are
// replaced (409); a straggler may come after a bake ended.
TEST(EditServer, AnswersChecksWhileSkinsBake) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("cantaloupe", dir);
  const std::string text = test::read_file(file);
  RunningServer server(file);
  std::array<int, 12> status{};
  std::vector<std::thread> bakes;
  for (size_t k = 0; k < status.size(); ++k) {
    bakes.emplace_back([&, k] {
      httplib::Client c = server.client();
      c.set_read_timeout(600, 0);
      status[k] = status_of(c.Post("/api/skin.glb", text, "text/plain"));
    });
  }
  EXPECT_TRUE(counts_reach(server, [](const EditWorkCounts& c) { return c.running == 1; }));
  const auto checked = server.client().Post("/api/check", text + "\n# edited\n", "text/plain");
  const EditWorkCounts during = server.counts();
  ASSERT_TRUE(checked);
  EXPECT_TRUE(nlohmann::json::parse(checked->body)["ok"]) << checked->body;
  EXPECT_EQ(during.finished, 0) << "the check waited for a bake";
  for (std::thread& t : bakes) t.join();
  for (const int s : status) EXPECT_TRUE(s == 200 || s == 409) << s;
  const EditWorkCounts after = server.counts();
  EXPECT_EQ(after.finished + after.superseded, 12);
  EXPECT_LE(after.finished, 3);
  EXPECT_EQ(static_cast<int>(std::count(status.begin(), status.end(), 200)), after.finished);
}

}  // namespace
}  // namespace cutaway
