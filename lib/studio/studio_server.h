#pragma once
// `sdgbehave studio`: a local web server (cpp-httplib) for one scene. Every
// request needs the access token printed with the URL; the Host and Origin
// headers must name the server itself (no DNS rebinding, no cross-site
// requests); bad requests get 4xx answers with a message, never a crash.
// All scene work runs on one thread, which owns the GL context and the
// Python interpreter.
#include <cstdint>
#include <functional>
#include <string>

#include "studio/studio_session.h"

namespace sdg::studio {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;                   // 0: a free port
  std::string token;              // "" = a random one
};

// Serves until the process is stopped (SIGINT/SIGTERM) or `stop` returns
// true (polled). `ready` gets the URL to open once the server listens.
// Throws SceneError for an invalid scene (before listening) and RunError
// when the port cannot be bound.
void serveStudio(const StudioOptions& studio, const ServerOptions& server, const std::function<void(const std::string&)>& ready);

// 32 random bytes from the OS, as hex.
std::string randomToken();

}  // namespace sdg::studio
