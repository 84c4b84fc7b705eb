#pragma once
// `sdgbehave studio`: a local web server (cpp-httplib) for one scene. Every
// request needs the access token printed with the URL (the favicon aside);
// the Host and Origin headers must name the server itself (no DNS
// rebinding, no cross-site requests); bad requests get 4xx answers with a
// message saying what was wrong, never a crash. All scene work runs on one
// thread, which owns the GL context and the Python interpreter.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "studio/studio_session.h"

namespace sdg::studio {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;                   // 0: a free port
  std::string token;              // "" = a random one
};

// Documented limit on a request body (JSON); larger ones get 413.
inline constexpr size_t kMaxRequestBody = size_t(1) << 20;

class StudioServer {
 public:
  // Loads the scene (SceneError for an invalid one, before anything
  // listens), then binds the port (RunError when it cannot).
  StudioServer(const StudioOptions& studio, const ServerOptions& server);
  // Stops serving and waits for the handlers.
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  // The URL to open, with the token.
  std::string url() const;
  int port() const;
  const std::string& token() const;
  // Serves on a thread of its own until stop() or the destructor.
  void start();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Serves until the process gets SIGINT or SIGTERM. `ready` gets the URL to
// open once the server listens. Throws as StudioServer's constructor.
void serveStudio(const StudioOptions& studio, const ServerOptions& server, const std::function<void(const std::string&)>& ready);

// 32 random bytes from the OS, as hex.
std::string randomToken();

}  // namespace sdg::studio
