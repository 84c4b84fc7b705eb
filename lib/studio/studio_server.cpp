#include "studio/studio_server.h"

#include <csignal>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <future>
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

void sendJson(httplib::Response& res, const Json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& message) {
  sendJson(res, Json{{"error", message}}, status);
}

Json parseBody(const httplib::Request& req) {
  try {
    Json body = Json::parse(req.body);
    if (!body.is_object()) throw StudioError(400, "the request body must be a JSON object");
    return body;
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

// Wraps a handler: scene errors and bad requests become 4xx, the rest 500.
httplib::Server::Handler guarded(std::function<void(const httplib::Request&, httplib::Response&)> handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
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
      sendError(res, 500, e.what());
    }
  };
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

void serveStudio(const StudioOptions& studio, const ServerOptions& options,
                 const std::function<void(const std::string&)>& ready) {
  // Block the stop signals in every thread; this one waits for them below.
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

  SessionThread session(studio);  // loads the scene: SceneError before anything listens
  const std::string token = options.token.empty() ? randomToken() : options.token;

  RenderJob render;  // destroyed after the server: a waiting render outlives no handler
  httplib::Server server;
  int port = options.port;
  std::vector<std::string> hosts = {options.host};
  if (options.host == "127.0.0.1" || options.host == "localhost" || options.host == "::1")
    hosts = {"127.0.0.1", "localhost", "[::1]"};

  server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
    // DNS rebinding: the Host must be this server.
    const std::string host = req.get_header_value("Host");
    bool hostOk = false;
    for (const std::string& h : hosts) hostOk = hostOk || host == h + ":" + std::to_string(port);
    if (!hostOk && (options.host == "0.0.0.0" || options.host == "::")) {
      // Listening on every address: any IP literal or localhost, never a
      // name (DNS rebinding comes through names).
      const std::string suffix = ":" + std::to_string(port);
      const std::string name = host.ends_with(suffix) ? host.substr(0, host.size() - suffix.size()) : "";
      hostOk = name == "localhost" || (!name.empty() && name.find_first_not_of("0123456789.") == std::string::npos) ||
               (name.size() > 2 && name.front() == '[' && name.back() == ']' &&
                name.find_first_not_of("0123456789abcdefABCDEF:[]") == std::string::npos);
    }
    if (!hostOk) {
      sendError(res, 421, "wrong Host header '" + host + "'");
      return httplib::Server::HandlerResponse::Handled;
    }
    // Cross-site requests: a browser's Origin must be this server too.
    if (req.has_header("Origin")) {
      const std::string origin = req.get_header_value("Origin");
      bool originOk = false;
      for (const std::string& h : hosts) originOk = originOk || origin == "http://" + h + ":" + std::to_string(port);
      if (!originOk) {
        sendError(res, 403, "requests from origin '" + origin + "' are refused");
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    if (req.path.find("..") != std::string::npos) {
      sendError(res, 400, "a path with '..' is refused");
      return httplib::Server::HandlerResponse::Handled;
    }
    const std::string given = req.has_param("token") ? req.get_param_value("token") : req.get_header_value("X-Studio-Token");
    if (given != token) {
      sendError(res, 403, "missing or wrong access token; open the URL sdgbehave studio printed");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  server.Get("/", guarded([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_header("Content-Security-Policy", "default-src 'self'; style-src 'self' 'unsafe-inline'; script-src 'self' 'unsafe-inline'; img-src 'self' blob: data:");
    res.set_content(kStudioPage, "text/html; charset=utf-8");
  }));
  server.Get("/api/state", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.state(); }));
  }));
  server.Get("/api/tree", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.tree(); }));
  }));
  server.Get("/api/behaviors", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.behaviors(); }));
  }));
  server.Get("/api/files", guarded([&](const httplib::Request& req, httplib::Response& res) {
    const std::string kind = req.has_param("kind") ? req.get_param_value("kind") : "";
    sendJson(res, session.call([&](StudioSession& s) { return s.files(kind); }));
  }));
  server.Get("/api/diff", guarded([&](const httplib::Request&, httplib::Response& res) {
    res.set_content(session.call([](StudioSession& s) { return s.diff(); }), "text/plain; charset=utf-8");
  }));
  server.Post("/api/edit", guarded([&](const httplib::Request& req, httplib::Response& res) {
    Json body = parseBody(req);
    if (!body.contains("prim") || !body["prim"].is_string() || !body.contains("keys") || !body["keys"].is_array() ||
        body["keys"].empty() || !body.contains("value"))
      throw StudioError(400, "an edit is {\"prim\": PATH, \"keys\": [KEY, ...], \"value\": JSON}");
    std::vector<std::string> keys;
    for (const auto& k : body["keys"]) {
      // Names only: a key is written into the YAML text as it is.
      if (!k.is_string() || !isValidAttributeName(k.get<std::string>()))
        throw StudioError(400, "keys are attribute or behavior names (identifiers joined by ':'), found " + k.dump());
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
  }));
  server.Post("/api/behavior", guarded([&](const httplib::Request& req, httplib::Response& res) {
    Json body = parseBody(req);
    if (!body.contains("prim") || !body["prim"].is_string() || !body.contains("behavior") ||
        !body["behavior"].is_string() || !body.contains("action") || !body["action"].is_string())
      throw StudioError(400, "expected {\"prim\": PATH, \"behavior\": NAME, \"action\": \"attach\" | \"detach\"}");
    const std::string prim = body["prim"], behavior = body["behavior"], action = body["action"];
    if (action != "attach" && action != "detach") throw StudioError(400, "action is attach or detach, found " + action);
    sendJson(res, session.call([&](StudioSession& s) {
      return s.setAttached(prim, behavior, action == "attach");
    }));
  }));
  server.Get("/api/preview", guarded([&](const httplib::Request& req, httplib::Response& res) {
    const uint64_t frame = frameParam(req);
    const std::string pass = req.has_param("pass") ? req.get_param_value("pass") : "rgb";
    const std::string camera = req.has_param("camera") ? req.get_param_value("camera") : "";
    std::vector<uint8_t> png = session.call([&](StudioSession& s) { return s.preview(frame, pass, camera); });
    res.set_header("Cache-Control", "no-store");
    res.set_content(std::string(png.begin(), png.end()), "image/png");
  }));
  server.Get("/api/record", guarded([&](const httplib::Request& req, httplib::Response& res) {
    const uint64_t frame = frameParam(req);
    sendJson(res, session.call([&](StudioSession& s) { return s.record(frame); }));
  }));
  server.Post("/api/preroll", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.preroll(); }));
  }));
  server.Post("/api/seed", guarded([&](const httplib::Request& req, httplib::Response& res) {
    Json body = parseBody(req);
    if (!body.contains("seed") || !body["seed"].is_number_integer()) throw StudioError(400, "expected {\"seed\": INT}");
    const int64_t seed = body["seed"].get<int64_t>();
    session.call([seed](StudioSession& s) {
      s.setSeed(seed);
      return 0;
    });
    sendJson(res, Json{{"seed", seed}});
  }));
  server.Post("/api/render", guarded([&](const httplib::Request& req, httplib::Response& res) {
    Json body = parseBody(req);
    if (!body.contains("frames") || !body["frames"].is_number_unsigned() || !body.contains("name") ||
        !body["name"].is_string())
      throw StudioError(400, "expected {\"frames\": N, \"name\": FOLDER_NAME}");
    auto [text, flags] = session.call([](StudioSession& s) { return std::make_pair(s.text(), s.runFlags()); });
    render.start(studio.scene.scenePath, text, body["frames"].get<uint64_t>(), body["name"].get<std::string>(), flags);
    sendJson(res, render.status());
  }));
  server.Get("/api/render", guarded([&](const httplib::Request&, httplib::Response& res) { sendJson(res, render.status()); }));
  server.Get("/api/render/contact_sheet", guarded([&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(render.contactSheet(), "image/png");
  }));
  server.Post("/api/reload", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.reload(); }));
  }));
  server.Post("/api/save", guarded([&](const httplib::Request&, httplib::Response& res) {
    sendJson(res, session.call([](StudioSession& s) { return s.save(); }));
  }));
  server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) sendError(res, res.status, "no such page or API call");
  });

  // SO_REUSEADDR only: with SO_REUSEPORT (cpp-httplib's default) a second
  // studio on the same port would share it silently.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const void*>(&yes), sizeof yes);
  });
  if (port == 0) port = server.bind_to_any_port(options.host);
  else if (!server.bind_to_port(options.host, port)) port = -1;
  if (port <= 0) throw RunError("studio: cannot listen on " + options.host + ":" + std::to_string(options.port));
  std::thread listener([&] { server.listen_after_bind(); });
  ready("http://" + (options.host == "::1" ? "[::1]" : options.host) + ":" + std::to_string(port) + "/?token=" + token);
  int signal = 0;
  sigwait(&stopSignals, &signal);
  log::info("studio: stopping");
  server.stop();
  listener.join();
}

}  // namespace sdg::studio
