#include "studio/studio_server.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <thread>

#include <httplib.h>

#include "core/diagnostics.h"
#include "core/log.h"
#include "scene_io/prim_reader.h"
#include "studio/render_job.h"

// The page, compiled in (lib/studio/page/index.html).
extern const char kStudioPage[];

namespace sdg::studio {
namespace {

using Json = nlohmann::ordered_json;

// A 16 x 16 PNG: the boxes pass's outline on the header's slate.
constexpr char kFavicon[] =
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x10\x00\x00\x00\x10"
    "\x08\x02\x00\x00\x00\x90\x91\x68\x36\x00\x00\x00\x2d\x49\x44\x41\x54\x78\xda\x63\xd0\x35\x75\x20"
    "\x09\x31\xd0\x51\xc3\x87\x09\x0a\x78\x10\x76\x0d\xb8\x4c\xc5\xa7\x61\xce\x8e\x0b\x68\x68\x54\x03"
    "\xa5\xc1\x4a\x5a\xc4\x0d\x9a\xc4\x07\x00\x01\xf6\xfc\x01\xb8\x1f\x9b\x35\x00\x00\x00\x00\x49\x45"
    "\x4e\x44\xae\x42\x60\x82";

// Runs every scene call on one thread: the one that made the GL context and
// started Python. Handlers wait for their call's result.
class SessionThread {
 public:
  explicit SessionThread(const StudioOptions& options) {
    std::promise<void> started;
    std::future<void> ready = started.get_future();
    thread_ = std::thread([this, options, &started] {
      try {
        session_ = std::make_unique<StudioSession>(options);
        started.set_value();
      } catch (...) {
        started.set_exception(std::current_exception());
        return;
      }
      loop();
    });
    try {
      ready.get();
    } catch (...) {
      thread_.join();
      throw;
    }
  }
  ~SessionThread() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  template <typename F>
  auto call(F&& f) -> decltype(f(std::declval<StudioSession&>())) {
    using R = decltype(f(std::declval<StudioSession&>()));
    auto task = std::make_shared<std::packaged_task<R()>>([this, f = std::forward<F>(f)]() mutable {
      session_->checkFile();
      return f(*session_);
    });
    std::future<R> result = task->get_future();
    {
      std::lock_guard lock(mutex_);
      queue_.push_back([task] { (*task)(); });
    }
    wake_.notify_one();
    return result.get();
  }

 private:
  void loop() {
    while (true) {
      std::function<void()> job;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_ && queue_.empty()) break;
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      job();
    }
    session_.reset();  // GL context and Python objects go on their own thread
  }

  std::unique_ptr<StudioSession> session_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
};

// Invalid bytes in a message (a camera name in a URL, say) are replaced,
// never a reason for a 500.
void sendJson(httplib::Response& res, const Json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(-1, ' ', false, Json::error_handler_t::replace), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& message) {
  sendJson(res, Json{{"error", message}}, status);
}

// The byte offset of the first byte that is not well-formed UTF-8, if any.
std::optional<size_t> invalidUtf8At(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    size_t n = b < 0x80 ? 1 : (b >> 5) == 6 ? 2 : (b >> 4) == 14 ? 3 : (b >> 3) == 30 ? 4 : 0;
    if (n == 0 || i + n > s.size()) return i;
    uint32_t code = n == 1 ? b : b & (0x7f >> n);
    for (size_t k = 1; k < n; ++k) {
      const auto c = static_cast<unsigned char>(s[i + k]);
      if ((c >> 6) != 2) return i;
      code = (code << 6) | (c & 0x3f);
    }
    // Overlong forms, surrogates and values past U+10FFFF are not UTF-8.
    static constexpr uint32_t kMinimum[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < kMinimum[n] || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return i;
    i += n;
  }
  return std::nullopt;
}

// A POST body as a JSON object; an empty body is {}.
Json parseBody(const std::string& body) {
  if (body.find_first_not_of(" \t\r\n") == std::string::npos) return Json::object();
  if (auto at = invalidUtf8At(body))
    throw StudioError(400, "the request body is not UTF-8 text: byte " + std::to_string(*at) + " is not valid UTF-8");
  try {
    Json parsed = Json::parse(body);
    if (!parsed.is_object()) throw StudioError(400, "the request body must be a JSON object");
    return parsed;
  } catch (const Json::parse_error& e) {
    throw StudioError(400, std::string("the request body is not JSON: ") + e.what());
  }
}

uint64_t frameParam(const httplib::Request& req) {
  if (!req.has_param("frame")) return 0;
  const std::string s = req.get_param_value("frame");
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
    throw StudioError(400, "frame must be a whole number, found '" + s + "'");
  return std::stoull(s);
}

// Runs a handler: scene errors and bad requests become 4xx, the rest 500.
template <typename F>
void guarded(const httplib::Request& req, httplib::Response& res, F&& handler) {
  try {
    handler();
  } catch (const StudioError& e) {
    sendError(res, e.status, e.what());
  } catch (const SceneError& e) {
    std::string messages;
    for (const Diagnostic& d : e.problems()) messages += (messages.empty() ? "" : "\n") + d.format();
    sendError(res, 400, messages);
  } catch (const Json::exception& e) {
    sendError(res, 400, std::string("bad request: ") + e.what());
  } catch (const std::exception& e) {
    log::error(std::string("studio: ") + req.path + ": " + e.what());
    sendError(res, 500, std::string("internal error: ") + e.what());
  }
}

// What each error status means, for answers that have no message of their
// own (those cpp-httplib gives before a handler runs).
std::string statusMessage(int status, const httplib::Request& req) {
  switch (status) {
    case 400: return "bad request: the request line or a header could not be read (each is at most 8 KB)";
    case 404: return "no such page or API call: " + req.method + " " + req.path;
    case 413: return "the request body is larger than the limit of " + std::to_string(kMaxRequestBody) + " bytes";
    case 414: return "the URL is longer than the limit of 8192 bytes";
    case 416: return "bad Range header";
    default: return "HTTP status " + std::to_string(status);
  }
}

// A regex that matches `path` exactly (cpp-httplib routes are regexes).
std::string exactly(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (std::string_view(".+*?()[]{}|^$\\").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string randomToken() {
  std::ifstream urandom("/dev/urandom", std::ios::binary);
  unsigned char bytes[32];
  if (!urandom.read(reinterpret_cast<char*>(bytes), sizeof bytes)) throw RunError("studio: cannot read /dev/urandom");
  static const char* kHex = "0123456789abcdef";
  std::string token;
  for (unsigned char b : bytes) token += kHex[b >> 4], token += kHex[b & 15];
  return token;
}

struct StudioServer::Impl {
  Impl(const StudioOptions& studioOptions, const ServerOptions& serverOptions)
      : options(serverOptions), session(studioOptions) {
    token = options.token.empty() ? randomToken() : options.token;
    if (options.host == "127.0.0.1" || options.host == "localhost" || options.host == "::1")
      hosts = {"127.0.0.1", "localhost", "[::1]"};
    else
      hosts = {options.host};
    scenePath = session.call([](StudioSession& s) { return s.scenePath(); });
    addRoutes();
    // SO_REUSEADDR only: with SO_REUSEPORT (cpp-httplib's default) a second
    // studio on the same port would share it silently.
    server.set_socket_options([](socket_t sock) {
      int yes = 1;
      setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const void*>(&yes), sizeof yes);
    });
    server.set_payload_max_length(kMaxRequestBody);
    port = options.port;
    if (port == 0) port = server.bind_to_any_port(options.host);
    else if (!server.bind_to_port(options.host, port)) port = -1;
    if (port <= 0) throw RunError("studio: cannot listen on " + options.host + ":" + std::to_string(options.port));
  }

  // GET (and so HEAD) `path`.
  void get(const std::string& path, std::function<void(const httplib::Request&, httplib::Response&)> handler) {
    allowed[path] = "GET, HEAD";
    server.Get(exactly(path), [handler](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] { handler(req, res); });
    });
  }

  // POST `path` with a JSON object body (none at all is {}).
  void post(const std::string& path, std::function<void(const Json&, httplib::Response&)> handler) {
    allowed[path] = "POST";
    server.Post(exactly(path), [this, handler](const httplib::Request& req, httplib::Response& res,
                                               const httplib::ContentReader& reader) {
      std::string body;
      if (!readBody(req, res, reader, body)) return;
      guarded(req, res, [&] { handler(parseBody(body), res); });
    });
  }

  // The body, read here rather than by cpp-httplib, which waits for the
  // connection to close when a POST has neither Content-Length nor chunks
  // (a body-less POST, as `curl -X POST` sends it, has no body: RFC 9112
  // 6.3). False when it could not be read; the answer is set then.
  static bool readBody(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
                       std::string& body) {
    if (!req.has_header("Content-Length") && !req.has_header("Transfer-Encoding")) return true;
    bool tooLarge = false;
    const bool read = reader([&](const char* data, size_t length) {
      if (body.size() + length > kMaxRequestBody) return !(tooLarge = true);
      body.append(data, length);
      return true;
    });
    if (read) return true;
    if (tooLarge || res.status == 413) sendError(res, 413, statusMessage(413, req));
    else
      sendError(res, 400, "the request body could not be read: it ended before its Content-Length (" +
                              req.get_header_value("Content-Length") + " bytes) or stalled for 5 s");
    return false;
  }

  // 405 with Allow for a route of another method, else 404.
  void noRoute(const httplib::Request& req, httplib::Response& res) {
    auto it = allowed.find(req.path);
    if (it == allowed.end()) return sendError(res, 404, statusMessage(404, req));
    res.set_header("Allow", it->second);
    sendError(res, 405, req.method + " is not allowed on " + req.path + "; allowed: " + it->second);
  }

  bool hostAllowed(const std::string& host) const {
    for (const std::string& h : hosts)
      if (host == h + ":" + std::to_string(port)) return true;
    if (options.host != "0.0.0.0" && options.host != "::") return false;
    // Listening on every address: any IP literal or localhost, never a
    // name (DNS rebinding comes through names).
    const std::string suffix = ":" + std::to_string(port);
    const std::string name = host.ends_with(suffix) ? host.substr(0, host.size() - suffix.size()) : "";
    return name == "localhost" || (!name.empty() && name.find_first_not_of("0123456789.") == std::string::npos) ||
           (name.size() > 2 && name.front() == '[' && name.back() == ']' &&
            name.find_first_not_of("0123456789abcdefABCDEF:[]") == std::string::npos);
  }

  httplib::Server::HandlerResponse screen(const httplib::Request& req, httplib::Response& res) {
    using Handled = httplib::Server::HandlerResponse;
    // DNS rebinding: the Host must be this server.
    const std::string host = req.get_header_value("Host");
    if (!hostAllowed(host)) {
      sendError(res, 421, "wrong Host header '" + host + "'");
      return Handled::Handled;
    }
    // Cross-site requests: a browser's Origin must be this server too.
    if (req.has_header("Origin")) {
      const std::string origin = req.get_header_value("Origin");
      bool originOk = false;
      for (const std::string& h : hosts) originOk = originOk || origin == "http://" + h + ":" + std::to_string(port);
      if (!originOk) {
        sendError(res, 403, "requests from origin '" + origin + "' are refused");
        return Handled::Handled;
      }
    }
    if (req.path.find("..") != std::string::npos) {
      sendError(res, 400, "a path with '..' is refused");
      return Handled::Handled;
    }
    // Browsers ask for the icon without the page's token; it is no secret.
    if (req.path == "/favicon.ico" && (req.method == "GET" || req.method == "HEAD")) return Handled::Unhandled;
    const std::string given = req.has_param("token") ? req.get_param_value("token") : req.get_header_value("X-Studio-Token");
    if (given != token) {
      sendError(res, 403, "missing or wrong access token; open the URL sdgbehave studio printed");
      return Handled::Handled;
    }
    if (req.method != "GET" && req.method != "HEAD" && req.method != "POST") {
      noRoute(req, res);
      return Handled::Handled;
    }
    return Handled::Unhandled;
  }

  void addRoutes();

  ServerOptions options;
  SessionThread session;
  std::string token, scenePath;
  std::vector<std::string> hosts;
  int port = 0;
  std::map<std::string, std::string> allowed;  // path -> the methods its route takes
  RenderJob render;  // destroyed after the server: a waiting render outlives no handler
  httplib::Server server;
  std::thread listener;
  std::atomic<bool> listenerEnded = false;
};

void StudioServer::Impl::addRoutes() {
  server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) { return screen(req, res); });
  get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_header("Content-Security-Policy", "default-src 'self'; style-src 'self' 'unsafe-inline'; script-src 'self' 'unsafe-inline'; img-src 'self' blob: data:");
    res.set_content(kStudioPage, "text/html; charset=utf-8");
  });
  get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "max-age=86400");
    res.set_content(kFavicon, sizeof kFavicon - 1, "image/png");
  });
  get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.state(); }));
  });
  get("/api/tree", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.tree(); }));
  });
  get("/api/behaviors", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.behaviors(); }));
  });
  get("/api/files", [this](const httplib::Request& req, httplib::Response& res) {
    const std::string kind = req.has_param("kind") ? req.get_param_value("kind") : "";
    sendJson(res, session.call([&](StudioSession& s) { return s.files(kind); }));
  });
  get("/api/diff", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(session.call([](StudioSession& s) { return s.diff(); }), "text/plain; charset=utf-8");
  });
  post("/api/edit", [this](const Json& body, httplib::Response& res) {
    if (!body.contains("prim") || !body["prim"].is_string() || !body.contains("keys") || !body["keys"].is_array() ||
        body["keys"].empty() || !body.contains("value"))
      throw StudioError(400, "an edit is {\"prim\": PATH, \"keys\": [KEY, ...], \"value\": JSON}");
    std::vector<std::string> keys;
    for (const auto& k : body["keys"]) {
      // Names only: a key is written into the YAML text as it is.
      if (!k.is_string() || !isValidAttributeName(k.get<std::string>()))
        throw StudioError(400, "keys are attribute or behavior names (identifiers joined by ':'), found " +
                                   k.dump(-1, ' ', false, Json::error_handler_t::replace));
      keys.push_back(k.get<std::string>());
    }
    // What a page may change is values: not which assets, scripts or
    // plugins load, not a prim's type.
    if (keys.front() == "reference" || keys.front() == "type" || keys.front() == "attributes")
      throw StudioError(400, "the studio edits values; change '" + keys.front() + "' in the file");
    if (keys.front() == "behaviors" && keys.size() != 3)
      throw StudioError(400, "a behavior's variable is [\"behaviors\", BEHAVIOR, VARIABLE]");
    const std::string prim = body["prim"].get<std::string>();
    const std::string value = body["value"].dump();
    if (body.contains("in") && (!body["in"].is_string() || (body["in"] != "scene" && body["in"] != "asset")))
      throw StudioError(400, "\"in\" is \"scene\" (the default: a local override) or \"asset\"");
    const bool inAsset = body.contains("in") && body["in"] == "asset";
    sendJson(res, session.call([&](StudioSession& s) { return s.edit(prim, keys, value, inAsset); }));
  });
  post("/api/behavior", [this](const Json& body, httplib::Response& res) {
    if (!body.contains("prim") || !body["prim"].is_string() || !body.contains("behavior") ||
        !body["behavior"].is_string() || !body.contains("action") || !body["action"].is_string())
      throw StudioError(400, "expected {\"prim\": PATH, \"behavior\": NAME, \"action\": \"attach\" | \"detach\"}");
    const std::string prim = body["prim"], behavior = body["behavior"], action = body["action"];
    if (action != "attach" && action != "detach") throw StudioError(400, "action is attach or detach, found " + action);
    sendJson(res, session.call([&](StudioSession& s) { return s.setAttached(prim, behavior, action == "attach"); }));
  });
  get("/api/preview", [this](const httplib::Request& req, httplib::Response& res) {
    const uint64_t frame = frameParam(req);
    const std::string pass = req.has_param("pass") ? req.get_param_value("pass") : "rgb";
    const std::string camera = req.has_param("camera") ? req.get_param_value("camera") : "";
    std::vector<uint8_t> png = session.call([&](StudioSession& s) { return s.preview(frame, pass, camera); });
    res.set_header("Cache-Control", "no-store");
    res.set_content(std::string(png.begin(), png.end()), "image/png");
  });
  get("/api/record", [this](const httplib::Request& req, httplib::Response& res) {
    const uint64_t frame = frameParam(req);
    sendJson(res, session.call([&](StudioSession& s) { return s.record(frame); }));
  });
  post("/api/preroll", [this](const Json&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.preroll(); }));
  });
  post("/api/seed", [this](const Json& body, httplib::Response& res) {
    if (!body.contains("seed") || !body["seed"].is_number_integer()) throw StudioError(400, "expected {\"seed\": INT}");
    const int64_t seed = body["seed"].get<int64_t>();
    session.call([seed](StudioSession& s) {
      s.setSeed(seed);
      return 0;
    });
    sendJson(res, Json{{"seed", seed}});
  });
  post("/api/render", [this](const Json& body, httplib::Response& res) {
    if (!body.contains("frames") || !body["frames"].is_number_unsigned() || !body.contains("name") ||
        !body["name"].is_string())
      throw StudioError(400, "expected {\"frames\": N, \"name\": FOLDER_NAME}");
    const uint64_t frames = body["frames"].get<uint64_t>();
    // `run --frames N` decides the frames written, iterations included.
    auto [text, flags, total] = session.call([frames](StudioSession& s) {
      return std::make_tuple(s.text(), s.runFlags(), frames ? s.framePlan(frames).total() : 0);
    });
    render.start(scenePath, text, frames, total, body["name"].get<std::string>(), flags);
    sendJson(res, render.status());
  });
  get("/api/render", [this](const httplib::Request&, httplib::Response& res) { sendJson(res, render.status()); });
  get("/api/render/contact_sheet", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(render.contactSheet(), "image/png");
  });
  post("/api/reload", [this](const Json&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.reload(); }));
  });
  post("/api/save", [this](const Json& body, httplib::Response& res) {
    if (body.contains("overwrite") && !body["overwrite"].is_boolean())
      throw StudioError(400, "\"overwrite\" is true or false");
    const bool overwrite = body.value("overwrite", false);
    sendJson(res, session.call([overwrite](StudioSession& s) { return s.save(overwrite); }));
  });
  // Last: a POST to any other path, its body read first (see readBody).
  server.Post(".*", [this](const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader) {
    std::string body;
    if (readBody(req, res, reader, body)) noRoute(req, res);
  });
  server.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (res.status == 404 && res.body.empty()) noRoute(req, res);  // a GET of a POST route: 405
    else if (res.body.empty()) sendError(res, res.status, statusMessage(res.status, req));
  });
}

StudioServer::StudioServer(const StudioOptions& studio, const ServerOptions& server)
    : impl_(std::make_unique<Impl>(studio, server)) {}

StudioServer::~StudioServer() { stop(); }

std::string StudioServer::url() const {
  return "http://" + (impl_->options.host == "::1" ? "[::1]" : impl_->options.host) + ":" + std::to_string(impl_->port) +
         "/?token=" + impl_->token;
}

int StudioServer::port() const { return impl_->port; }

const std::string& StudioServer::token() const { return impl_->token; }

void StudioServer::start() {
  if (impl_->listener.joinable()) return;
  impl_->listener = std::thread([this] {
    impl_->server.listen_after_bind();
    impl_->listenerEnded = true;
  });
  // Until the listener runs, cpp-httplib's stop() would do nothing and
  // leave it accepting forever.
  while (!impl_->server.is_running() && !impl_->listenerEnded)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void StudioServer::stop() {
  impl_->server.stop();
  if (impl_->listener.joinable()) impl_->listener.join();
}

void serveStudio(const StudioOptions& studio, const ServerOptions& options,
                 const std::function<void(const std::string&)>& ready) {
  // Block the stop signals in every thread; this one waits for them below.
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

  StudioServer server(studio, options);
  server.start();
  ready(server.url());
  int signal = 0;
  sigwait(&stopSignals, &signal);
  log::info("studio: stopping");
  server.stop();
}

}  // namespace sdg::studio
