#include "app/edit/edit_server.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include <arpa/inet.h>
#include <fcntl.h>
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <strings.h>
#include <sys/eventfd.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <unistd.h>

#include "app/edit/web_files.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/file_read.h"
#include "batch/variant_set.h"
#include "cut/piece_views.h"
#include "diffusion/diffusion.h"
#include "export/gltf_export.h"
#include "export/volume_files.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"
#include "model/curves.h"
#include "model/model_builder.h"
#include "variation/grains.h"
#include "variation/variation.h"
#include "volume/interior_volume.h"

namespace cutaway {

namespace {

/// A parsed template and its DS model.
struct Built {
  Template tmpl;
  DsModel model;
};

Built build(std::string_view text, const std::filesystem::path& template_path) {
  Template tmpl =
      parse_template(text, template_path.filename().string(), template_path.parent_path().string());
  DsModel model = build_model(tmpl);
  check_grain_limits(tmpl, model);  // as `cutaway check` does
  return {std::move(tmpl), std::move(model)};
}

nlohmann::json verdict_of(const InputError& e) {
  return {{"ok", false},          {"file", e.loc().file},
          {"line", e.loc().line}, {"column", e.loc().column},
          {"field", e.field()},   {"rule", e.rule()},
          {"message", e.what()}};
}

nlohmann::json vec3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

/// `points` (metres) fitted as the template means them, in template units.
nlohmann::json fitted(const Polyline2& points, bool closed, bool smooth, double units) {
  nlohmann::json out = nlohmann::json::array();
  for (const glm::dvec2& p : fit_curve(points, closed, smooth))
    out.push_back({p.x / units, p.y / units});
  return out;
}

/// The fitted profile and section loops of every surface (check_template_text's "curves").
nlohmann::json fitted_curves(const Template& t) {
  nlohmann::json curves = nlohmann::json::array();
  for (const SurfaceSpec& s : t.surfaces) {
    nlohmann::json c = {{"profile", nlohmann::json::array()},
                        {"sections", nlohmann::json::array()}};
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

/// `body` as JSON text. Bytes that are not UTF-8 (a template file's name may hold any) become
/// U+FFFD instead of making dump() throw.
std::string json_text(const nlohmann::json& body) {
  return body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void reply_json(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(json_text(body), "application/json");
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

/// The bytes of the template file at `path`, or nullopt when there is none yet. Read with
/// read_regular_file: opened without blocking (a FIFO put in its place would block an open, and
/// every request behind it), and read only when it is a regular file of at most
/// kMaxInputFileBytes (the template parser's own limit).
/// @throws FileReadError "cannot read PATH: RULE" (not a regular file, too large, or the
///         system's reason)
std::optional<std::string> read_template_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) && !ec) return std::nullopt;  // a new template
  return read_regular_file(path, kMaxInputFileBytes);
}

using Clock = std::chrono::steady_clock;

/// Waits until `fd` has one of `events` (or an error or hang-up, so that the next call on it
/// says which), at most until `deadline`; false when the deadline passed first.
bool await(int fd, short events, Clock::time_point deadline) {
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    pollfd p{fd, events, 0};
    const int n = ::poll(&p, 1, static_cast<int>(std::max<long long>(left.count(), 0)));
    if (n > 0) return true;
    if (n == 0) return false;
    if (errno != EINTR) return true;  // the next call on the socket reports the error
  }
}

/// One accepted connection, as the HTTP library's stream, with the bounds of a request: its
/// head and body must arrive before a deadline set at its first byte, and no more than an
/// allowance of bytes is read for it (the head's, then the body's once the head is parsed).
/// Reads go through a small buffer, as the library reads a request's head a byte at a time.
/// The socket is non-blocking; the connection does not close it (its server does).
class Connection final : public httplib::Stream {
 public:
  /// `fd`: a connected socket; `timeout`: the request timeout of EditServerOptions.
  Connection(int fd, std::chrono::milliseconds timeout) : fd_(fd), timeout_(timeout) {
    ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) | O_NONBLOCK);
  }

  /// Waits up to `idle` for the next request's first byte (or the client closing: the read
  /// then finds the end), then starts its bounds: the deadline, the head's allowance. False
  /// when nothing came within `idle`.
  bool await_request(std::chrono::milliseconds idle) {
    if (next_ == end_ && !await(fd_, POLLIN, Clock::now() + idle)) return false;
    deadline_ = Clock::now() + timeout_;
    allowance_ = kMaxRequestHeadBytes;
    overran_ = timed_out_ = close_after_ = false;
    return true;
  }
  /// The head was parsed: its body may take `bytes` more (framing included).
  void allow_body(size_t bytes) { allowance_ = bytes; }
  /// The connection is closed once the answer is written (its body was not all read).
  void close_after_answer() { close_after_ = true; }
  /// Whether the connection is to be closed after this request: asked for, or a read broke a
  /// bound (what was left unread would be taken for the next request).
  bool closing() const { return close_after_ || overran_ || timed_out_; }
  bool overran() const { return overran_; }      ///< a read found the allowance spent
  bool timed_out() const { return timed_out_; }  ///< a read found the deadline passed
  /// Whether the client has closed its side or the socket was shut down (stop()): no one will
  /// read the answer.
  bool client_gone() const {
    pollfd p{fd_, POLLRDHUP, 0};
    return ::poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR));
  }

  /// Before closing a connection whose request body was left unread: ends the sending side,
  /// then reads and drops what the client still sends (at most `bytes`, for at most `time`),
  /// so that the client reads the answer rather than a reset.
  void linger(size_t bytes, std::chrono::milliseconds time) {
    ::shutdown(fd_, SHUT_WR);
    const Clock::time_point until = Clock::now() + time;
    while (bytes > 0 && await(fd_, POLLIN, until)) {
      const ssize_t n = ::recv(fd_, buffer_.data(), std::min(buffer_.size(), bytes), 0);
      if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK)) return;
      if (n > 0) bytes -= static_cast<size_t>(n);
    }
  }

  bool is_readable() const override { return next_ != end_ || await(fd_, POLLIN, deadline_); }
  bool is_writable() const override { return await(fd_, POLLOUT, Clock::now() + timeout_); }

  ssize_t read(char* out, size_t size) override {
    if (next_ == end_) {
      const ssize_t got = receive();
      if (got <= 0) return got;
    }
    const size_t n = std::min(size, end_ - next_);
    std::memcpy(out, buffer_.data() + next_, n);
    next_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* data, size_t size) override {
    const Clock::time_point deadline = Clock::now() + timeout_;
    for (;;) {
      const ssize_t n = ::send(fd_, data, size, MSG_NOSIGNAL);
      if (n >= 0) return n;
      if (errno == EINTR) continue;
      if ((errno != EAGAIN && errno != EWOULDBLOCK) || !await(fd_, POLLOUT, deadline)) return -1;
    }
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address_of(::getpeername, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address_of(::getsockname, ip, port);
  }
  socket_t socket() const override { return fd_; }

 private:
  /// Refills the buffer: the bytes received, 0 when the client closed, -1 on an error, the
  /// deadline or the allowance.
  ssize_t receive() {
    if (allowance_ == 0) {
      overran_ = true;
      return -1;
    }
    for (;;) {
      const ssize_t n = ::recv(fd_, buffer_.data(), std::min(buffer_.size(), allowance_), 0);
      if (n >= 0) {
        allowance_ -= static_cast<size_t>(n);
        next_ = 0;
        end_ = static_cast<size_t>(n);
        return n;
      }
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
      if (!await(fd_, POLLIN, deadline_)) {
        timed_out_ = true;
        return -1;
      }
    }
  }

  template <class Name>
  void address_of(Name name, std::string& ip, int& port) const {
    sockaddr_in a{};
    socklen_t length = sizeof a;
    std::array<char, INET_ADDRSTRLEN> text{};
    if (name(fd_, reinterpret_cast<sockaddr*>(&a), &length) == 0 && a.sin_family == AF_INET &&
        ::inet_ntop(AF_INET, &a.sin_addr, text.data(), text.size())) {
      ip = text.data();
      port = ntohs(a.sin_port);
    }
  }

  int fd_;
  std::chrono::milliseconds timeout_;
  Clock::time_point deadline_ = Clock::now();
  size_t allowance_ = 0;
  bool overran_ = false, timed_out_ = false, close_after_ = false;
  std::array<char, 4096> buffer_{};
  size_t next_ = 0, end_ = 0;  // the unread bytes of buffer_
};

/// The connection whose request this thread serves (each connection has a thread of its own,
/// on which the HTTP library calls the handlers).
thread_local Connection* this_connection = nullptr;

/// Answers `status` with `message` to `req` and closes the connection afterwards: for refusals
/// made before the request's body was read. The answer says "Connection: close" once (the HTTP
/// library adds it itself when the client asked for it).
void refuse_and_close(const httplib::Request& req, httplib::Response& res, int status,
                      const std::string& message) {
  reply_json(res, status, {{"ok", false}, {"message", message}});
  if (req.get_header_value("Connection") != "close") res.set_header("Connection", "close");
  this_connection->close_after_answer();
}

/// Why a request's head bars it from being read further (refuse_and_close's status and
/// message), or nullopt when it may be served: the methods served are GET, HEAD and POST, and
/// only a POST has a body; a body must be plain text (no Content-Encoding, no Transfer-Encoding
/// but chunked, no multipart form) and must state its length, at most `max_body_bytes`, or be
/// chunked.
std::optional<std::pair<int, std::string>> head_refusal(const httplib::Request& req,
                                                        size_t max_body_bytes) {
  using Refusal = std::pair<int, std::string>;
  if (req.method != "GET" && req.method != "HEAD" && req.method != "POST")
    return Refusal{405, "the method " + quoted(req.method) + " is not served (GET and POST are)"};
  const std::string coding = req.get_header_value("Content-Encoding");
  const std::string transfer = req.get_header_value("Transfer-Encoding");
  const bool chunked = strcasecmp(transfer.c_str(), "chunked") == 0;
  if ((!coding.empty() && strcasecmp(coding.c_str(), "identity") != 0) ||
      (!transfer.empty() && !chunked))
    return Refusal{415, "compressed request bodies are refused: send the text as it is"};
  if (req.is_multipart_form_data())
    return Refusal{415, "send the template text as the body, not as a form"};
  const Refusal bodiless{400, "only a POST has a body"};
  if (chunked) {
    if (req.method != "POST") return bodiless;
    if (req.has_header("Content-Length"))
      return Refusal{400, "a chunked body must not have a Content-Length"};
    return std::nullopt;
  }
  if (!req.has_header("Content-Length")) {
    if (req.method == "POST")
      return Refusal{411, "a POST must have a Content-Length (or a chunked body)"};
    return std::nullopt;
  }
  const std::string stated = req.get_header_value("Content-Length");
  uint64_t length = 0;
  const auto [end, error] = std::from_chars(stated.data(), stated.data() + stated.size(), length);
  if (error != std::errc() || end != stated.data() + stated.size() || stated.empty())
    return Refusal{400, "a bad Content-Length " + quoted(stated)};
  if (length > max_body_bytes)
    return Refusal{413, "request bodies are limited to " + std::to_string(max_body_bytes) +
                            " bytes, not " + stated};
  if (length > 0 && req.method != "POST") return bodiless;
  return std::nullopt;
}

/// The views of the pages whose requests compute, each with its own turn in the work queue:
/// the cutting page's volume, the editor's model (picture, glTF, skin), its cut and its strip
/// of variants.
enum class WorkView { Volume, Model, Cut, Variants };
constexpr size_t kWorkViews = 4;

/// What became of a request handed to WorkQueue::run.
enum class Admission {
  Ran,         ///< its job ran
  Superseded,  ///< a newer request of its view came while it waited: its job did not run
  Busy,        ///< the queue held its bound: its job did not run
};

/// The work requests: per view one runs at a time and at most one waits; a newer request of a
/// view replaces the one waiting and tells the one running (which stops early where it can).
/// At most `bound` requests are admitted at once, running or waiting, over all views; one more
/// is refused at once. Requests that are not work (checks, saves) never pass through it.
class WorkQueue {
 public:
  /// @pre bound >= 1
  explicit WorkQueue(int bound) : bound_(bound) {}

  /// Runs `job(superseded)` in `view`'s turn, once the job of the view running has ended;
  /// `superseded()` tells `job` that a newer request of the view has come. Exceptions of `job`
  /// pass through.
  Admission run(WorkView view,
                const std::function<void(const std::function<bool()>& superseded)>& job) {
    std::unique_lock<std::mutex> lock(mutex_);
    Slot& slot = slots_[static_cast<size_t>(view)];
    const bool replaces = slot.waiting != 0;  // takes the place of the request waiting
    if (!replaces && counts_.running + counts_.waiting >= bound_) {
      ++counts_.turned_away;
      return Admission::Busy;
    }
    if (!replaces) ++counts_.waiting;
    const uint64_t ticket = ++slot.newest;
    slot.waiting = ticket;
    changed_.notify_all();  // the one waiting, if any, gives up
    changed_.wait(lock, [&] { return !slot.running || slot.newest != ticket; });
    if (slot.newest != ticket) {
      ++counts_.superseded;
      return Admission::Superseded;
    }
    slot.waiting = 0;
    slot.running = true;
    --counts_.waiting;
    ++counts_.running;
    lock.unlock();
    struct Ending {  // the next job may start, even when this one throws
      WorkQueue& queue;
      Slot& slot;
      ~Ending() {
        const std::lock_guard<std::mutex> relock(queue.mutex_);
        slot.running = false;
        --queue.counts_.running;
        ++queue.counts_.finished;
        queue.changed_.notify_all();
      }
    } ending{*this, slot};
    job([this, &slot, ticket] {
      const std::lock_guard<std::mutex> relock(mutex_);
      return slot.newest != ticket;
    });
    return Admission::Ran;
  }

  /// The counts so far (volumes_sampled is not the queue's: 0).
  EditWorkCounts counts() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

 private:
  struct Slot {
    uint64_t newest = 0;   // the ticket of the view's newest request
    uint64_t waiting = 0;  // the ticket of the request waiting, 0 when none
    bool running = false;
  };
  const int bound_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::array<Slot, kWorkViews> slots_{};
  EditWorkCounts counts_;
};

/// Answers a work request that did not run (`admission` Superseded: 409; Busy: 503 with
/// Retry-After); a request whose job ran is left as its job answered it.
void answer_admission(Admission admission, httplib::Response& res) {
  if (admission == Admission::Superseded) {
    reply_json(res, 409, {{"ok", false}, {"message", "a newer request of this view replaced it"}});
  } else if (admission == Admission::Busy) {
    reply_json(res, 503, {{"ok", false}, {"message", "the editor is busy; retry in a moment"}});
    res.set_header("Retry-After", "1");
  }
}

/// A template text that built, shared by the requests about it, which may run side by side,
/// with the cpu diffusion backends of its cuts, each made at the first cut that needs it.
class BuiltText {
 public:
  BuiltText(std::string text, Built built) : text(std::move(text)), built(std::move(built)) {}

  const std::string text;
  const Built built;

  /// The backend of cuts with a PMVC cube of `cube` texels a face; from any thread.
  const DiffusionBackend& section_diffusion(int cube) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::unique_ptr<DiffusionBackend>& backend = backends_[cube];
    if (!backend) backend = make_cpu_diffusion(built.model, {cube, 0});
    return *backend;
  }

 private:
  mutable std::mutex mutex_;
  mutable std::map<int, std::unique_ptr<DiffusionBackend>> backends_;
};

/// A random token of 32 hex digits (128 bits of getrandom), new for each server.
/// @throws std::system_error when the system gives no random bytes
std::string random_token() {
  std::array<unsigned char, 16> bytes{};
  for (size_t got = 0; got < bytes.size();) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0 && errno != EINTR)
      throw std::system_error(errno, std::generic_category(), "getrandom");
    if (n > 0) got += static_cast<size_t>(n);
  }
  constexpr std::string_view kHex = "0123456789abcdef";
  std::string token;
  for (const unsigned char b : bytes) {
    token += kHex[b >> 4];
    token += kHex[b & 15];
  }
  return token;
}

/// Whether `given` is `token`, compared in a time that does not depend on where they differ.
bool same_token(std::string_view given, std::string_view token) {
  if (given.size() != token.size()) return false;
  unsigned char difference = 0;
  for (size_t i = 0; i < token.size(); ++i)
    difference |= static_cast<unsigned char>(given[i] ^ token[i]);
  return difference == 0;
}

/// Where index.html and cut.html hold the server's token: the server fills in the content.
constexpr std::string_view kTokenPlaceholder = R"(<meta name="cutaway-token" content="">)";

/// The embedded page `file` with `token` filled into its token meta tag.
std::string page_with_token(std::string_view file, const std::string& token) {
  const std::optional<std::string_view> page = editor_web_file(file);
  CUTAWAY_CHECK(page.has_value());
  std::string html(*page);
  const size_t at = html.find(kTokenPlaceholder);
  CUTAWAY_CHECK(at != std::string::npos);
  html.replace(at, kTokenPlaceholder.size(),
               R"(<meta name="cutaway-token" content=")" + token + "\">");
  return html;
}

/// An interior volume's files for the cutting page (volume_files_of), by kind, and the name of
/// the template they are of.
struct VolumeFiles {
  std::string name;
  std::map<std::string, std::string> files;
};

/// Answers the file `kind` of `volume`.
void answer_volume_file(const VolumeFiles& volume, const std::string& kind,
                        httplib::Response& res) {
  const std::string type = kind == "json"  ? "application/json"
                           : kind == "glb" ? "model/gltf-binary"
                                           : "image/png";
  res.set_content(volume.files.at(kind), type);
}

/// Whether `asked` is the volume's template's `name`; answers 404 when not.
bool names_volume(const std::string& asked, const std::string& name, httplib::Response& res) {
  if (asked == name) return true;
  reply_json(res, 404, {{"ok", false}, {"message", "this editor serves the volume of " + name}});
  return false;
}

/// The template text `text` without what does not change its template, comments and layout:
/// yaml-cpp's dump of its parse. Texts that differ only there have one volume.
/// @throws InputError when `text` is not YAML
std::string template_content(std::string_view text, const std::filesystem::path& template_path) {
  return YAML::Dump(parse_yaml(text, template_path.filename().string()).node());
}

/// httplib's server as a router: this file accepts and serves the connections and hands each
/// request to process_request() (httplib 0.11's own loop has a fixed pool of threads, 8 on a
/// small machine, a listen backlog of 5 and no bound on the time a request takes to arrive).
class Router : public httplib::Server {
 public:
  using httplib::Server::process_request;
};

/// How long a connection closed on a refusal keeps reading what its client still sends.
constexpr std::chrono::milliseconds kLingerTime{1000};

/// The listen backlog: connections the kernel queues before they are accepted.
constexpr int kListenBacklog = 512;

/// A socket listening on 127.0.0.1:`port` (0: any free port), or -1 when it cannot bind.
/// SO_REUSEADDR only (no SO_REUSEPORT, with which a second process could bind the same port
/// and take the editor's requests): a restarted editor takes its port back from connections
/// still closing, and a taken port fails to bind.
int listen_on_loopback(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0 ||
      ::listen(fd, kListenBacklog) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

/// The port `fd` is bound to.
int bound_port(int fd) {
  sockaddr_in a{};
  socklen_t length = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
  return ntohs(a.sin_port);
}

/// Answers a connection over the bound 503 and closes it, without waiting for the client.
void turn_away(int fd, int max_connections) {
  const std::string body =
      json_text({{"ok", false},
                 {"message", "the server is serving " + std::to_string(max_connections) +
                                 " connections, its most; retry in a moment"}});
  const std::string answer =
      "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nContent-Length: " +
      std::to_string(body.size()) + "\r\nRetry-After: 1\r\nConnection: close\r\n\r\n" + body;
  [[maybe_unused]] const ssize_t sent =
      ::send(fd, answer.data(), answer.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  ::close(fd);
}

/// The router's exception handler: 500 with the error's message.
void answer_exception(const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
  std::string why = "unknown error";
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    why = e.what();
  } catch (...) {
  }
  reply_json(res, 500, {{"ok", false}, {"message", why}});
}

/// The files of the interior volume of `b`'s template (no seed) with `across` voxels along its
/// skin's longest edge, as the cutting page loads them, by kind ("json", "colour.png",
/// "structure.png", "material.png", "glb"): the sidecar naming the flipbooks NAME.KIND, and the
/// whole object referring to NAME.json. PMVC as cut faces have it (cpu backend, the default cube),
/// with the template's Perlin modulation.
/// @throws InputError when the volume has more regions than a flipbook numbers
std::map<std::string, std::string> volume_files_of(const Built& b, int across) {
  const std::string& name = b.tmpl.name;
  const auto diffusion = make_cpu_diffusion(b.model, DiffusionOptions{});
  Outcome<InteriorVolume> grid = volume_grid(b.model, voxel_length_across(b.model, across));
  CUTAWAY_CHECK(grid.has_value());  // `across` is bounded well below kMaxVolumeVoxels
  const ColourModulation modulation(b.tmpl.npr, 0);
  const InteriorVolume volume =
      sample_interior_volume(b.model, *diffusion, std::move(*grid), 0, &modulation, 1.0);
  Outcome<std::vector<NamedFile>> made = volume_files(volume, name, name, -1, false);
  if (!made) throw InputError({b.tmpl.file, 0, 0}, "(file)", made.reason());
  std::map<std::string, std::string> files;
  for (auto& [file, bytes] : *made) files[file.substr(name.size() + 1)] = std::move(bytes);
  GltfSceneOptions gltf;
  gltf.camera_and_lights = false;
  gltf.scene_extras["interior_volume"] = {{"sidecar", name + ".json"}};
  files["glb"] =
      scene_to_glb(whole_object_assets(Variant{b.tmpl, b.model}, *diffusion, 1.0, 0), gltf);
  return files;
}

/// GET /NAME.js and /NAME.css: the page's embedded scripts and style sheets.
void get_web_file(const httplib::Request& req, httplib::Response& res) {
  const std::string type = req.matches[2] == "js" ? "text/javascript" : "text/css";
  const std::optional<std::string_view> text =
      editor_web_file(req.matches[1].str() + "." + req.matches[2].str());
  if (text) res.set_content(std::string(*text), type + "; charset=utf-8");
  else reply_json(res, 404, {{"ok", false}, {"message", "no such file"}});
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

Check check_request(std::string_view host, std::string_view origin, int port) {
  const std::string p = std::to_string(port);
  if (host != "127.0.0.1:" + p && host != "localhost:" + p)
    return Check::none("the Host header must be 127.0.0.1:" + p + " or localhost:" + p + ", not " +
                       quoted(host));
  if (!origin.empty() && origin != "http://127.0.0.1:" + p && origin != "http://localhost:" + p)
    return Check::none("requests from other sites are refused (Origin " + quoted(origin) + ")");
  return {};
}

struct EditServer::Impl {
  EditServerOptions options;
  EditRenderers renderers;
  Router router;
  int listen_fd = -1;
  int wake_fd = -1;  // an eventfd: stop() wakes run()'s accept loop with it
  int port = 0;
  // The open connections' sockets (stop() shuts them down), each served by a thread of its own.
  std::mutex connections_mutex;
  std::condition_variable connection_ended;
  std::set<int> connections;
  bool stopping = false;
  std::string token = random_token();  // what requests to /api/ must carry (kTokenHeader)
  std::unique_ptr<WorkQueue> work;     // the requests that compute
  std::mutex render;                   // one picture at a time is drawn (OpenGL)
  // The last text that built: the page asks for the verdict, the model and cuts at several
  // heights of one text, which is built once. The lock is held while a text builds.
  std::mutex build_mutex;
  std::shared_ptr<const BuiltText> latest;
  // The interior volume of the saved template last asked for: the template_content it is of,
  // and its files. The lock is held only to look up or store.
  std::mutex volume_mutex;
  std::string volume_content;
  std::shared_ptr<const VolumeFiles> volume;
  std::atomic<int> volumes_sampled{0};

  ~Impl() {
    if (listen_fd >= 0) ::close(listen_fd);
    if (wake_fd >= 0) ::close(wake_fd);
  }

  /// The template and model of `text`, from the last request when it sent the same text.
  /// Waits at most for one other text to build, never for work.
  /// @throws InputError as build()
  std::shared_ptr<const BuiltText> built_for(const std::string& text) {
    const std::lock_guard<std::mutex> lock(build_mutex);
    if (!latest || latest->text != text) {
      latest.reset();
      latest = std::make_shared<const BuiltText>(text, build(text, options.template_path));
    }
    return latest;
  }

  /// Answers a work request of `view` about the template text `body`: in the view's turn of
  /// the work queue (answer_admission() when it does not get one), builds the text (422 with
  /// the verdict) and runs `answer(built, superseded)`, as answer_or_refuse(). A request
  /// whose client has gone by its turn is dropped.
  void work_on(WorkView view, const std::string& body, httplib::Response& res,
               const std::function<void(const BuiltText&, const std::function<bool()>&)>& answer) {
    answer_admission(work->run(view,
                               [&](const std::function<bool()>& superseded) {
                                 if (this_connection->client_gone()) return;
                                 answer_or_refuse(res,
                                                  [&] { answer(*built_for(body), superseded); });
                               }),
                     res);
  }

  /// The volume made for `content` (template_content), or null when it was not made.
  std::shared_ptr<const VolumeFiles> volume_of(const std::string& content) {
    const std::lock_guard<std::mutex> lock(volume_mutex);
    return volume_content == content ? volume : nullptr;
  }

  /// The body of a POST, read within the bounds (max_body_bytes; the connection's allowance
  /// and deadline); nullopt after answering 413, 408 or 400 (and closing the connection after
  /// the answer) when it is too large, late or cut short.
  std::optional<std::string> read_body(const httplib::Request& req,
                                       const httplib::ContentReader& reader,
                                       httplib::Response& res) {
    std::string body;
    bool too_large = false;
    const bool read = reader([&](const char* data, size_t size) {
      too_large = size > options.max_body_bytes - body.size();
      if (!too_large) body.append(data, size);
      return !too_large;
    });
    if (read) return body;
    Connection& c = *this_connection;
    if (too_large || c.overran())
      refuse_and_close(req, res, 413,
                       "request bodies are limited to " + std::to_string(options.max_body_bytes) +
                           " bytes");
    else if (c.timed_out())
      refuse_and_close(req, res, 408,
                       "the request did not arrive within " +
                           std::to_string(options.request_timeout.count()) + " ms");
    else refuse_and_close(req, res, 400, "the request's body is cut short or badly chunked");
    return std::nullopt;
  }

  /// Serves POST `pattern` with `handler`, given the request body once read_body() has read it.
  void post(const std::string& pattern,
            std::function<void(const httplib::Request&, httplib::Response&, const std::string&)>
                handler) {
    router.Post(pattern, [this, handler = std::move(handler)](
                             const httplib::Request& req, httplib::Response& res,
                             const httplib::ContentReader& reader) {
      if (const std::optional<std::string> body = read_body(req, reader, res))
        handler(req, res, *body);
    });
  }

  /// Serves the connection `fd` (in `connections`) until it closes, is idle too long, has had
  /// kRequestsPerConnection requests or breaks a bound; then closes it.
  void serve_connection(int fd) {
    {
      Connection connection(fd, options.request_timeout);
      this_connection = &connection;
      for (int served = 0; served < kRequestsPerConnection; ++served) {
        if (!connection.await_request(options.idle_timeout)) break;
        const bool last = served + 1 == kRequestsPerConnection;
        bool client_closes = false;
        if (!router.process_request(connection, last, client_closes, nullptr) || client_closes ||
            connection.closing())
          break;
      }
      if (connection.closing()) connection.linger(options.max_body_bytes, kLingerTime);
      this_connection = nullptr;
    }
    const std::lock_guard<std::mutex> lock(connections_mutex);
    connections.erase(fd);
    ::close(fd);
    connection_ended.notify_all();
  }

  /// Serves the accepted connection `fd` on a thread of its own, or turns it away (503) when
  /// max_connections are open or the server stops.
  void accept_connection(int fd) {
    std::unique_lock<std::mutex> lock(connections_mutex);
    if (!stopping && connections.size() < static_cast<size_t>(options.max_connections)) {
      connections.insert(fd);
      try {
        std::thread([this, fd] { serve_connection(fd); }).detach();
        return;
      } catch (const std::system_error&) {  // no thread to be had: as over the bound
        connections.erase(fd);
      }
    }
    lock.unlock();
    turn_away(fd, options.max_connections);
  }

  /// The pre-routing handler: before a request's body is read, who may ask (403 otherwise:
  /// check_request(), and the token on every request to /api/), and whether its head bars the
  /// body (head_refusal()); a request that passes may send a body of max_body_bytes.
  httplib::Server::HandlerResponse screen_request(const httplib::Request& req,
                                                  httplib::Response& res);
  /// GET / and /cut.html: the embedded page `file` with the server's token, not to be cached
  /// (a restarted server has another token).
  void get_page(std::string_view file, httplib::Response& res) const;
  /// GET /lib/NAME/PATH: a file of the library NAME the page imports, from its own folder
  /// (library_file keeps requests inside it).
  void get_library_file(const httplib::Request& req, httplib::Response& res);
  /// GET /api/template: the file as it is on disk; no lock (saves rename a whole file into
  /// place).
  void get_template(const httplib::Request& req, httplib::Response& res);
  /// POST /api/volume/NAME.KIND: a file of the interior volume of the template file as it is
  /// on disk (KIND json, colour.png, structure.png, material.png or glb; volume_files_of),
  /// NAME being its template's name. The name is compared before any work: 404 for another
  /// name or no file yet, 422 with the verdict when the file does not build. The volume is
  /// sampled once per template_content, in the Volume view's turn of the work queue.
  void post_volume_file(const httplib::Request& req, httplib::Response& res,
                        const std::string& body);
  /// POST /api/check: the verdict on the text, as check_template_text() gives it (200 either
  /// way); never waits for work.
  void post_check(const httplib::Request& req, httplib::Response& res, const std::string& body);
  /// POST /api/model.png: the see-through model of the text (Model view).
  void post_model_png(const httplib::Request& req, httplib::Response& res, const std::string& body);
  /// POST /api/model.glb: the model of the text as binary glTF (Model view).
  void post_model_glb(const httplib::Request& req, httplib::Response& res, const std::string& body);
  /// POST /api/skin.glb: the object of the text uncut, its skin baked as scenes bake it (the
  /// skin's patterns, their relief as a normal map, the Perlin modulation of seed 0), as
  /// binary glTF with the preview's camera, the studio lights and the exposure (scenes' extras):
  /// what the outside looks like, lit as scenes are (Model view).
  void post_skin_glb(const httplib::Request& req, httplib::Response& res, const std::string& body);
  /// POST /api/section.png?y=Y[&coarse=1]: the text's cut at height Y (template units; Cut
  /// view).
  void post_section_png(const httplib::Request& req, httplib::Response& res,
                        const std::string& body);
  /// POST /api/variants.png[?count=N]: a strip of seeded variants (seeds 1..count, count 1..8,
  /// default 4): their mid-height cuts, as `cutaway variants` draws its contact sheet
  /// (Variants view). A strip being made when a newer request comes ends after the variant it
  /// is on, answered 409; one whose client left is dropped after the variant it is on.
  void post_variants_png(const httplib::Request& req, httplib::Response& res,
                         const std::string& body);
  /// POST /api/save: writes the text to the template file. The text is checked and the answer
  /// made before the file is written, so that an answer is never an error about a file that
  /// was written; no work is waited for, and the write renames a whole file into place.
  void post_save(const httplib::Request& req, httplib::Response& res, const std::string& body);
};

httplib::Server::HandlerResponse EditServer::Impl::screen_request(const httplib::Request& req,
                                                                  httplib::Response& res) {
  const Check allowed =
      check_request(req.get_header_value("Host"), req.get_header_value("Origin"), port);
  if (!allowed) {
    refuse_and_close(req, res, 403, allowed.reason());
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.path.starts_with("/api/") &&
      !same_token(req.get_header_value(std::string(kTokenHeader)), token)) {
    refuse_and_close(req, res, 403,
                     "requests to /api/ need the token of the page this editor serves (" +
                         std::string(kTokenHeader) + "); reload the page");
    return httplib::Server::HandlerResponse::Handled;
  }
  if (const auto refusal = head_refusal(req, options.max_body_bytes)) {
    refuse_and_close(req, res, refusal->first, refusal->second);
    return httplib::Server::HandlerResponse::Handled;
  }
  // A chunked body's framing may take up to a head's worth of bytes more than its content.
  this_connection->allow_body(options.max_body_bytes + kMaxRequestHeadBytes);
  return httplib::Server::HandlerResponse::Unhandled;
}

void EditServer::Impl::get_page(std::string_view file, httplib::Response& res) const {
  res.set_header("Cache-Control", "no-store");
  res.set_content(page_with_token(file, token), "text/html; charset=utf-8");
}

void EditServer::Impl::get_library_file(const httplib::Request& req, httplib::Response& res) {
  for (const WebLibrary& lib : options.libraries) {
    if (lib.name != req.matches[1]) continue;
    if (const auto file = library_file(lib.folder, req.matches[2].str())) {
      res.set_content(read_file_bytes(*file), "text/javascript; charset=utf-8");
      return;
    }
  }
  reply_json(res, 404, {{"ok", false}, {"message", "no such library file"}});
}

void EditServer::Impl::get_template(const httplib::Request&, httplib::Response& res) {
  const std::string file = options.template_path.filename().string();
  try {
    const std::optional<std::string> text = read_template_file(options.template_path);
    reply_json(res, 200,
               {{"file", file}, {"exists", text.has_value()}, {"text", text.value_or("")}});
  } catch (const EnvironmentError& e) {
    reply_json(res, 500, {{"ok", false}, {"file", file}, {"message", e.what()}});
  }
}

void EditServer::Impl::post_volume_file(const httplib::Request& req, httplib::Response& res,
                                        const std::string&) {
  std::optional<std::string> text;
  try {
    text = read_template_file(options.template_path);
  } catch (const EnvironmentError& e) {
    reply_json(res, 500, {{"ok", false}, {"message", e.what()}});
    return;
  }
  if (!text) {
    reply_json(res, 404, {{"ok", false}, {"message", "the template is not saved yet"}});
    return;
  }
  const std::string name = req.matches[1], kind = req.matches[2];
  std::optional<std::string> content;
  answer_or_refuse(res, [&] { content = template_content(*text, options.template_path); });
  if (!content) return;  // answered with the verdict
  if (const std::shared_ptr<const VolumeFiles> made = volume_of(*content)) {
    if (names_volume(name, made->name, res)) answer_volume_file(*made, kind, res);
    return;
  }
  std::shared_ptr<const BuiltText> b;
  answer_or_refuse(res, [&] { b = built_for(*text); });
  if (!b || !names_volume(name, b->built.tmpl.name, res)) return;
  answer_admission(work->run(WorkView::Volume,
                             [&](const std::function<bool()>&) {
                               if (this_connection->client_gone()) return;
                               std::shared_ptr<const VolumeFiles> made =
                                   volume_of(*content);  // by a request before
                               answer_or_refuse(res, [&] {
                                 if (!made) {
                                   made = std::make_shared<const VolumeFiles>(VolumeFiles{
                                       b->built.tmpl.name,
                                       volume_files_of(b->built, options.volume_voxels_across)});
                                   ++volumes_sampled;
                                   const std::lock_guard<std::mutex> lock(volume_mutex);
                                   volume_content = *content;
                                   volume = made;
                                 }
                                 answer_volume_file(*made, kind, res);
                               });
                             }),
                   res);
}

void EditServer::Impl::post_check(const httplib::Request&, httplib::Response& res,
                                  const std::string& body) {
  try {
    reply_json(res, 200, verdict_of(built_for(body)->built));
  } catch (const InputError& e) {
    reply_json(res, 200, verdict_of(e));
  }
}

void EditServer::Impl::post_model_png(const httplib::Request&, httplib::Response& res,
                                      const std::string& body) {
  work_on(WorkView::Model, body, res, [&](const BuiltText& b, const auto&) {
    const std::lock_guard<std::mutex> lock(render);
    res.set_content(renderers.model_png(b.built.model), "image/png");
  });
}

void EditServer::Impl::post_model_glb(const httplib::Request&, httplib::Response& res,
                                      const std::string& body) {
  work_on(WorkView::Model, body, res, [&](const BuiltText& b, const auto&) {
    res.set_content(model_to_glb(b.built.model, GltfModelOptions{}), "model/gltf-binary");
  });
}

void EditServer::Impl::post_skin_glb(const httplib::Request&, httplib::Response& res,
                                     const std::string& body) {
  work_on(WorkView::Model, body, res, [&](const BuiltText& b, const auto&) {
    GltfSceneOptions gltf;
    gltf.camera_and_lights = true;  // lit as scenes are: the page renders by the file's lights
    res.set_content(scene_to_glb(whole_object_assets(Variant{b.built.tmpl, b.built.model},
                                                     b.section_diffusion(options.section_cube), 1.0,
                                                     0),
                                 gltf),
                    "model/gltf-binary");
  });
}

void EditServer::Impl::post_section_png(const httplib::Request& req, httplib::Response& res,
                                        const std::string& body) {
  const Outcome<double> y = parse_decimal(req.get_param_value("y"), "y");
  if (!y) {
    reply_json(res, 400, {{"ok", false}, {"message", y.reason() + " (template units)"}});
    return;
  }
  // While the plane is dragged the page asks for coarse cuts, then a full one.
  const int cube =
      req.get_param_value("coarse") == "1" ? options.coarse_section_cube : options.section_cube;
  work_on(WorkView::Cut, body, res, [&](const BuiltText& b, const auto&) {
    Plane plane;
    plane.point = {0, *y * b.built.tmpl.metres_per_unit, 0};
    plane.normal = {0, 1, 0};
    CrossSectionOptions o;
    o.edge_m = b.built.tmpl.edge_m;
    const Outcome<CrossSection> section =
        make_cross_section(b.built.model, plane, b.section_diffusion(cube), o);
    if (!section) {
      reply_json(res, 422, {{"ok", false}, {"message", section.reason()}});
      return;
    }
    const std::lock_guard<std::mutex> lock(render);
    res.set_content(renderers.section_png(*section), "image/png");
  });
}

void EditServer::Impl::post_variants_png(const httplib::Request& req, httplib::Response& res,
                                         const std::string& body) {
  const std::string given = req.has_param("count") ? req.get_param_value("count") : "4";
  const int count = given.size() == 1 && given[0] >= '1' && given[0] <= '8' ? given[0] - '0' : 0;
  if (count == 0) {
    reply_json(res, 400, {{"ok", false}, {"message", "count must be a whole number from 1 to 8"}});
    return;
  }
  const int cube = options.variant_cube;
  const DiffusionFactory diffusion = [cube](const DsModel& m) {
    return make_cpu_diffusion(m, {cube, 0});
  };
  work_on(
      WorkView::Variants, body, res,
      [&](const BuiltText& b, const std::function<bool()>& superseded) {
        std::vector<Outcome<CrossSection>> sections;
        for (int seed = 1; seed <= count; ++seed) {
          if (superseded()) return answer_admission(Admission::Superseded, res);
          if (this_connection->client_gone()) return;  // no one to answer
          sections.push_back(variant_section(make_variant(b.built.tmpl, seed), diffusion));
        }
        if (std::none_of(sections.begin(), sections.end(), [](const auto& c) { return bool(c); })) {
          reply_json(res, 422,
                     {{"ok", false},
                      {"message", "no variant has a cut at mid-height: " + sections[0].reason()}});
          return;
        }
        const std::lock_guard<std::mutex> lock(render);
        res.set_content(renderers.variants_png(std::move(sections)), "image/png");
      });
}

void EditServer::Impl::post_save(const httplib::Request&, httplib::Response& res,
                                 const std::string& body) {
  bool valid = false;
  answer_or_refuse(res, [&] { valid = built_for(body) != nullptr; });
  if (!valid) return;  // answered with the verdict
  answer_or_refuse(res, [&] {
    const std::string answer =
        json_text({{"ok", true}, {"file", options.template_path.filename().string()}});
    write_file_atomically(options.template_path, body);
    res.set_content(answer, "application/json");
  });
}

EditServer::EditServer(EditServerOptions options, EditRenderers renderers)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.options = std::move(options);
  s.renderers = std::move(renderers);
  s.work = std::make_unique<WorkQueue>(s.options.max_work_requests);
  // What the answers' Keep-Alive header says (serve_connection() does it).
  s.router.set_keep_alive_max_count(kRequestsPerConnection);
  s.router.set_keep_alive_timeout(
      std::chrono::ceil<std::chrono::seconds>(s.options.idle_timeout).count());
  s.router.set_exception_handler(answer_exception);
  s.router.set_pre_routing_handler(std::bind_front(&Impl::screen_request, &s));
  // The page: embedded files (no request names a file on disk), and the libraries it
  // imports, each from its own folder.
  s.router.Get("/", [&s](const httplib::Request&, httplib::Response& res) {
    s.get_page("index.html", res);
  });
  s.router.Get(R"(/([a-z_]+)\.(js|css))", get_web_file);
  s.router.Get(R"(/lib/([a-z]+)/(.+))", std::bind_front(&Impl::get_library_file, &s));
  s.router.Get("/api/template", std::bind_front(&Impl::get_template, &s));
  s.router.Get("/cut.html", [&s](const httplib::Request&, httplib::Response& res) {
    s.get_page("cut.html", res);
  });
  s.post(R"(/api/volume/([a-z0-9_-]+)\.(json|colour\.png|structure\.png|material\.png|glb))",
         std::bind_front(&Impl::post_volume_file, &s));
  s.post("/api/check", std::bind_front(&Impl::post_check, &s));
  s.post("/api/model.png", std::bind_front(&Impl::post_model_png, &s));
  s.post("/api/model.glb", std::bind_front(&Impl::post_model_glb, &s));
  s.post("/api/skin.glb", std::bind_front(&Impl::post_skin_glb, &s));
  s.post("/api/section.png", std::bind_front(&Impl::post_section_png, &s));
  s.post("/api/variants.png", std::bind_front(&Impl::post_variants_png, &s));
  s.post("/api/save", std::bind_front(&Impl::post_save, &s));

  s.listen_fd = listen_on_loopback(s.options.port);
  if (s.listen_fd < 0)
    throw EnvironmentError("port " + std::to_string(s.options.port) +
                           " on 127.0.0.1 is taken; pass another with --port");
  s.port = bound_port(s.listen_fd);
  s.wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (s.wake_fd < 0) throw std::system_error(errno, std::generic_category(), "eventfd");
}

EditServer::~EditServer() = default;

int EditServer::port() const { return impl_->port; }

const std::string& EditServer::token() const { return impl_->token; }

std::optional<std::string> EditServer::cutting_page_url() const {
  const std::filesystem::path& path = impl_->options.template_path;
  try {
    const std::optional<std::string> text = read_template_file(path);
    if (!text) return std::nullopt;
    const std::string name =
        parse_template(*text, path.filename().string(), path.parent_path().string()).name;
    return "http://127.0.0.1:" + std::to_string(impl_->port) + "/cut.html?volume=/api/volume/" +
           name + ".json&model=/api/volume/" + name + ".glb";
  } catch (const InputError&) {
    return std::nullopt;
  } catch (const EnvironmentError&) {
    return std::nullopt;
  }
}

EditWorkCounts EditServer::work_counts() const {
  EditWorkCounts counts = impl_->work->counts();
  counts.volumes_sampled = impl_->volumes_sampled;
  return counts;
}

void EditServer::run() {
  Impl& s = *impl_;
  for (;;) {
    std::array<pollfd, 2> ready{{{s.listen_fd, POLLIN, 0}, {s.wake_fd, POLLIN, 0}}};
    if (::poll(ready.data(), ready.size(), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (ready[1].revents != 0) break;  // stop()
    const int fd = ::accept4(s.listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd >= 0) {
      s.accept_connection(fd);
    } else if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
      // Out of descriptors or memory: the queued connections wait for some to be freed.
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ::close(s.listen_fd);
  s.listen_fd = -1;
  std::unique_lock<std::mutex> lock(s.connections_mutex);
  s.connection_ended.wait(lock, [&] { return s.connections.empty(); });
}

void EditServer::stop() {
  Impl& s = *impl_;
  {
    const std::lock_guard<std::mutex> lock(s.connections_mutex);
    s.stopping = true;
    for (const int fd : s.connections) ::shutdown(fd, SHUT_RDWR);
  }
  const uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(s.wake_fd, &one, sizeof one);
}

}  // namespace cutaway
