// The template editor's server (edit/edit_server.h): its security rules, each with a request
// that breaks it; the parser's verdict with line, column, field and rule; the pictures; and
// saving: every shipped template opened and saved unchanged keeps its model bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "edit/edit_server.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// A server on a free port for `template_path`, running on its own thread while in scope.
/// Its pictures are stand-ins that say what they were given (the OpenGL previews have tests
/// of their own).
class RunningServer {
 public:
  explicit RunningServer(const fs::path& template_path, size_t max_body = 1u << 20) {
    EditServerOptions o;
    o.template_path = template_path;
    o.port = 0;
    o.max_body_bytes = max_body;
    o.section_cube = 4;
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
    server_ = std::make_unique<EditServer>(o, r);
    thread_ = std::thread([this] { server_->run(); });
  }
  ~RunningServer() {
    server_->stop();
    thread_.join();
  }
  int port() const { return server_->port(); }
  /// A client that sends the server's own Host header.
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port());
    c.set_read_timeout(60, 0);
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

TEST(EditServer, RefusesForeignHostsAndOrigins) {
  EXPECT_EQ(request_refusal("127.0.0.1:8765", "", 8765), "");
  EXPECT_EQ(request_refusal("localhost:8765", "http://localhost:8765", 8765), "");
  EXPECT_NE(request_refusal("evil.example:8765", "", 8765), "");     // DNS rebinding
  EXPECT_NE(request_refusal("127.0.0.1:9999", "", 8765), "");        // another port
  EXPECT_NE(request_refusal("", "", 8765), "");                      // no Host at all
  EXPECT_NE(request_refusal("127.0.0.1:8765", "http://evil.example", 8765), "");
  EXPECT_NE(request_refusal("127.0.0.1:8765", "https://127.0.0.1:8765", 8765), "");

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
  EXPECT_EQ(status_of(c.Post("/api/save", {{"Origin", "http://evil.example"}}, "name: x",
                             "text/plain")),
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
  for (const char* bad : {"../outside.js", "sub/../../outside.js", "./index.js", ".hidden.js",
                          "notes.txt", "link.js", "sub//part.js", "/etc/passwd.js", "sub",
                          "missing.js", "a b.js", "sub/", ""})
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
  for (const char* path : {"/lib/yaml/../outside.js", "/lib/yaml/%2e%2e/outside.js",
                           "/lib/yaml/link.js", "/lib/yaml/notes.txt", "/lib/three/index.js",
                           "/lib/yaml/..%2foutside.js"})
    EXPECT_EQ(status_of(c.Get(path)), 404) << path;
  server.stop();
  serving.join();
}

TEST(EditServer, RefusesOversizedBodies) {
  const fs::path dir = test::fresh_dir("edit");
  const fs::path file = copy_template("tomato", dir);
  RunningServer server(file, 1000);
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
  EXPECT_EQ(bad["line"].get<int>(), 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')));
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

}  // namespace
}  // namespace cutaway
