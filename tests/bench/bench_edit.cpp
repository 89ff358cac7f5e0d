// Editor benchmark: the live feedback of `cutaway edit` (app/edit/edit_server.h) as the
// page asks for it, timed through HTTP on 127.0.0.1 with the OpenGL pictures: the verdict, the
// model's glTF, the cut at five new heights with the full cube and with the coarse cube the
// page uses while the plane is dragged, and the strip of four variants. The target is
// at most 0.5 s per cut update on the tomato; the paper's Table 1 gives its cut time (the
// whole cut, not a live update) for comparison.
// One line per template: check, glb, full cut mean / max, coarse cut mean / max, variants.
//
// Run:   make bench                       (builds and runs the `benchmarks` target)
//   or:  cmake --build build --target bench_edit && ./build/bench_edit [TEMPLATE...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <httplib.h>

#include "app/edit/edit_pictures.h"
#include "app/edit/edit_server.h"
#include "base/atomic_file.h"
#include "paper_table1.h"

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

/// Seconds one POST of `body` to `path` takes; -1 when it does not answer 200.
double timed_post(httplib::Client& client, const std::string& path, const std::string& body) {
  const auto t0 = Clock::now();
  const auto r = client.Post(path, body, "text/plain");
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  return r && r->status == 200 ? s : -1;
}

struct Times {
  double mean = 0, max = 0;
};

/// Cuts at five heights spread over [lo, hi], each new to the server.
Times cuts(httplib::Client& client, const std::string& body, double lo, double hi, bool coarse,
           double shift) {
  Times t;
  for (int k = 0; k < 5; ++k) {
    const double y = lo + (hi - lo) * (0.15 + 0.175 * k + shift);
    const double s = timed_post(
        client, "/api/section.png?y=" + std::to_string(y) + (coarse ? "&coarse=1" : ""), body);
    t.mean += s / 5;
    t.max = std::max(t.max, s);
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cutaway;
  std::vector<std::string> names(argv + 1, argv + argc);
  if (names.empty()) names = {"tomato", "kiwi", "onion", "strawberry"};
  std::string table1_source;
  const std::vector<bench::PaperRow> table1 = bench::read_table1(&table1_source);
  std::printf("# live feedback of `cutaway edit`, seconds per request through HTTP (target: a cut "
              "update <= 0.5 s on the tomato); paper: Table 1's cut time (%s)\n",
              table1_source.c_str());
  std::printf("%-11s %6s %6s %15s %15s %8s %7s\n", "template", "check", "glb", "cut mean/max",
              "coarse mean/max", "variants", "paper");
  for (const std::string& name : names) {
    const fs::path file = fs::path(CUTAWAY_SOURCE_DIR) / "templates" / (name + ".yaml");
    const std::string body = read_file_bytes(file);
    EditServerOptions o;
    o.template_path = file;  // nothing is saved
    o.port = 0;
    EditServer server(o, opengl_edit_pictures());
    std::thread serving([&] { server.run(); });
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(600, 0);
    client.set_default_headers({{std::string(kTokenHeader), server.token()}});
    const auto t0 = Clock::now();
    const auto verdict = client.Post("/api/check", body, "text/plain");
    const double check = std::chrono::duration<double>(Clock::now() - t0).count();
    const auto v = nlohmann::json::parse(verdict ? verdict->body : "{}", nullptr, false);
    if (!v.is_object() || !v.value("ok", false)) {
      std::printf("%-11s does not build: %s\n", name.c_str(),
                  verdict ? verdict->body.c_str() : "no answer");
    } else {
      const double lo = v["bbox_min"][1], hi = v["bbox_max"][1];
      const double glb = timed_post(client, "/api/model.glb", body);
      const Times full = cuts(client, body, lo, hi, false, 0.0);
      const Times coarse = cuts(client, body, lo, hi, true, 0.01);
      const double variants = timed_post(client, "/api/variants.png", body);
      const bench::PaperRow* row = bench::find_row(table1, name);
      std::printf("%-11s %6.3f %6.3f %7.3f/%7.3f %7.3f/%7.3f %8.2f %7s\n", name.c_str(), check, glb,
                  full.mean, full.max, coarse.mean, coarse.max, variants,
                  row ? row->cut_s.c_str() : "-");
    }
    std::fflush(stdout);
    server.stop();
    serving.join();
  }
  return 0;
}
