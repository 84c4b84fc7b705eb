// The studio's HTTP server without a browser, through raw sockets so that
// malformed requests can be sent: body-less POSTs, bad encodings, size
// limits, 405 with Allow, the favicon, one message per status; edits that
// `validate` would refuse (a wrong kind of file, a file outside the asset
// roots, an unreadable one) get a 4xx and leave the text and the preview
// as they were; the conflict flow (reload or overwrite); the frame plan.
#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "studio/studio_server.h"

using namespace sdg;
using namespace sdg::studio;
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

const std::string kSource = SDG_SOURCE_DIR;

struct Reply {
  int status = 0;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;
  std::string error() const {
    try {
      return Json::parse(body).at("error").get<std::string>();
    } catch (const std::exception&) {
      return "(no error message: " + body.substr(0, 200) + ")";
    }
  }
};

// Sends `request` as it is and reads the answer until the server closes the
// connection. `closeWrite` ends the request's bytes (a short body ends there).
Reply exchange(int port, const std::string& request, bool closeWrite = false) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  timeval timeout{30, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
  for (size_t sent = 0; sent < request.size();) {
    const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may answer (413) and stop reading
    sent += size_t(n);
  }
  if (closeWrite) ::shutdown(fd, SHUT_WR);
  std::string raw;
  char buffer[65536];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) raw.append(buffer, size_t(n));
  ::close(fd);
  Reply reply;
  const size_t end = raw.find("\r\n\r\n");
  if (end == std::string::npos) return reply;
  std::istringstream head(raw.substr(0, end));
  std::string line;
  std::getline(head, line);
  reply.status = std::stoi(line.substr(9, 3));
  while (std::getline(head, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    reply.headers[name] = line.substr(colon + 2);
  }
  reply.body = raw.substr(end + 4);
  return reply;
}

fs::path scratch(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("sdg_studio_server_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "scene" / "props");
  fs::create_directories(dir / "scene" / "textures");
  fs::create_directories(dir / "outside");
  return dir;
}

void writeFile(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* kScene = R"(# A mesh, a moving box and a camera.
version: 1
capture: {frames: 6, frames_per_iteration: 2, iterations: 3, seed: 3}
prims:
  /World: {}
  /World/Crate: {type: Mesh, asset: props/crate.glb, translate: [0, 0, 0.5]}
  /World/Box:
    type: Cube
    size: 0.5
    behaviors:
      locationRandomizer: {interval: 2, range:minPosition: [-1, -1, 0], range:maxPosition: [1, 1, 0]}
  /World/Sun: {type: DistantLight, inputs:intensity: 3000, rotateXYZ: [30, 10, 0]}
  /World/Cam: {type: Camera, translate: [0, -6, 4], rotateXYZ: [55, 0, 0]}
)";

// A studio on a copy of kScene (with a mesh, a texture, and a mesh outside
// the scene's folder), serving until the test ends.
struct Studio {
  fs::path dir, scene;
  std::unique_ptr<StudioServer> server;

  explicit Studio(const std::string& name) : dir(scratch(name)), scene(dir / "scene" / "scene.yaml") {
    writeFile(scene, kScene);
    fs::copy_file(kSource + "/scenes/props/crate.glb", dir / "scene" / "props" / "crate.glb");
    fs::copy_file(kSource + "/scenes/props/crate.obj", dir / "scene" / "props" / "crate.obj");
    fs::copy_file(kSource + "/scenes/props/crate.mtl", dir / "scene" / "props" / "crate.mtl");
    fs::copy_file(kSource + "/scenes/textures/wood.png", dir / "scene" / "textures" / "wood.png");
    fs::copy_file(kSource + "/scenes/props/crate.glb", dir / "outside" / "crate.glb");
    StudioOptions options;
    options.scene.scenePath = scene.string();
    ServerOptions serverOptions;
    serverOptions.token = "t0k3n";
    server = std::make_unique<StudioServer>(options, serverOptions);
    server->start();
  }
  ~Studio() {
    server.reset();
    fs::remove_all(dir);
  }

  std::string head(const std::string& method, const std::string& target, bool token = true) const {
    return method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(server->port()) + "\r\n" +
           (token ? "X-Studio-Token: t0k3n\r\n" : "") + "Connection: close\r\n";
  }
  Reply get(const std::string& target, bool token = true) const {
    return exchange(server->port(), head("GET", target, token) + "\r\n");
  }
  Reply post(const std::string& target, const std::string& body) const {
    return exchange(server->port(), head("POST", target) + "Content-Type: application/json\r\nContent-Length: " +
                                        std::to_string(body.size()) + "\r\n\r\n" + body);
  }
  Reply raw(const std::string& request, bool closeWrite = false) const {
    return exchange(server->port(), request, closeWrite);
  }
  Reply edit(const std::string& prim, const Json& keys, const Json& value) const {
    return post("/api/edit", Json{{"prim", prim}, {"keys", keys}, {"value", value}}.dump());
  }
};

}  // namespace

TEST_CASE("studio server: a POST without a body is an empty one, answered at once", "[studio]") {
  Studio studio("bodyless");
  for (const char* version : {"HTTP/1.1", "HTTP/1.0"}) {
    CAPTURE(version);
    const auto start = std::chrono::steady_clock::now();
    Reply r = studio.raw("POST /api/reload " + std::string(version) + "\r\nHost: 127.0.0.1:" +
                         std::to_string(studio.server->port()) + "\r\nX-Studio-Token: t0k3n\r\nConnection: close\r\n\r\n");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(r.status == 200);
    CHECK(Json::parse(r.body).at("reloaded") == studio.scene.string());
    CHECK(seconds < 2.0);  // cpp-httplib alone waits 5 s for the connection to close
  }
  CHECK(studio.raw(studio.head("POST", "/api/preroll") + "\r\n").status == 200);
  CHECK(studio.post("/api/save", "").status == 200);  // Content-Length: 0
}

TEST_CASE("studio server: bad encodings, sizes and methods get their own 4xx and message", "[studio]") {
  Studio studio("edges");
  std::map<int, std::string> messages;

  SECTION("a body that is not UTF-8 is a 400 saying so") {
    Reply r = studio.post("/api/seed", "{\"seed\": \"\xff\xfe\"}");
    CHECK(r.status == 400);
    CHECK(r.error() == "the request body is not UTF-8 text: byte 10 is not valid UTF-8");
    // Overlong forms and surrogates are not UTF-8 either; real text is fine.
    CHECK(studio.post("/api/seed", "{\"seed\": \"\xc0\xaf\"}").status == 400);
    CHECK(studio.post("/api/seed", "{\"seed\": \"\xed\xa0\x80\"}").status == 400);
    CHECK(studio.post("/api/seed", "{\"seed\": 5, \"note\": \"caf\xc3\xa9 \xf0\x9f\x93\xa6\"}").status == 200);
    // A name in the URL that is not UTF-8 is quoted in the answer, not a 500.
    r = studio.get("/api/preview?camera=%ff%fe");
    CHECK(r.status == 400);
    CHECK(r.error().find("is not a Camera of the scene") != std::string::npos);
    CHECK(studio.post("/api/seed", "{not json").error().starts_with("the request body is not JSON"));
  }
  SECTION("bodies above the documented limit are a 413, with a length or in chunks") {
    const std::string big(kMaxRequestBody + 1, ' ');
    Reply r = studio.post("/api/seed", big);
    CHECK(r.status == 413);
    CHECK(r.error() == "the request body is larger than the limit of 1048576 bytes");
    std::string chunked = studio.head("POST", "/api/seed") + "Transfer-Encoding: chunked\r\n\r\n";
    for (int i = 0; i < 3; ++i) chunked += "80000\r\n" + std::string(0x80000, ' ') + "\r\n";
    r = studio.raw(chunked + "0\r\n\r\n");
    CHECK(r.status == 413);
    CHECK(studio.post("/api/seed", std::string(kMaxRequestBody - 12, ' ') + "{\"seed\": 4}").status == 200);
  }
  SECTION("a body shorter than its Content-Length") {
    // cpp-httplib answers nothing to a client that closed its side, so this
    // waits for the server's 5 s read timeout.
    Reply r = studio.raw(studio.head("POST", "/api/seed") + "Content-Length: 100\r\n\r\n{\"seed\": 1");
    CHECK(r.status == 400);
    CHECK(r.error().starts_with("the request body could not be read: it ended before its Content-Length (100 bytes)"));
  }
  SECTION("each status has a message of its own") {
    Reply header = studio.raw(studio.head("GET", "/api/state") + "X-Big: " + std::string(100000, 'a') + "\r\n\r\n");
    Reply unknown = studio.get("/api/nothing");
    Reply longUrl = studio.get("/api/state?x=" + std::string(9000, 'a'));
    Reply tooLarge = studio.post("/api/seed", std::string(kMaxRequestBody + 1, ' '));
    Reply wrongMethod = studio.get("/api/save");
    CHECK(header.status == 400);
    CHECK(header.error() == "bad request: the request line or a header could not be read (each is at most 8 KB)");
    CHECK(unknown.status == 404);
    CHECK(unknown.error() == "no such page or API call: GET /api/nothing");
    CHECK(longUrl.status == 414);
    CHECK(longUrl.error() == "the URL is longer than the limit of 8192 bytes");
    CHECK(tooLarge.status == 413);
    CHECK(wrongMethod.status == 405);
    for (const Reply* r : {&header, &unknown, &longUrl, &tooLarge, &wrongMethod}) messages[r->status] = r->error();
    CHECK(messages.size() == 5);
    std::set<std::string> distinct;
    for (const auto& [status, message] : messages) distinct.insert(message);
    CHECK(distinct.size() == 5);
  }
  SECTION("a route asked with the wrong method is a 405 with Allow") {
    Reply r = studio.get("/api/save");
    CHECK(r.status == 405);
    CHECK(r.headers["allow"] == "POST");
    CHECK(r.error() == "GET is not allowed on /api/save; allowed: POST");
    r = studio.post("/api/state", "{}");
    CHECK(r.status == 405);
    CHECK(r.headers["allow"] == "GET, HEAD");
    r = studio.raw(studio.head("PUT", "/api/edit") + "Content-Length: 2\r\n\r\n{}");
    CHECK(r.status == 405);
    CHECK(r.headers["allow"] == "POST");
    r = studio.raw(studio.head("DELETE", "/api/nothing") + "\r\n");
    CHECK(r.status == 404);
  }
  SECTION("the favicon needs no token; everything else does") {
    Reply r = studio.get("/favicon.ico", false);
    CHECK(r.status == 200);
    CHECK(r.headers["content-type"] == "image/png");
    CHECK(r.body.starts_with("\x89PNG\r\n\x1a\n"));
    CHECK(studio.get("/", false).status == 403);
    CHECK(studio.get("/api/state", false).status == 403);
    CHECK(studio.post("/favicon.ico", "{}").status == 405);
  }
  SECTION("the server lives on") {
    CHECK(studio.get("/api/state").status == 200);
  }
}

TEST_CASE("studio server: an edit validate would refuse is a 4xx, text and preview stay as they were", "[studio]") {
  Studio studio("refused");
  writeFile(studio.dir / "scene" / "props" / "note.glb", "This is a note, not a mesh.\n");
  writeFile(studio.dir / "scene" / "props" / "empty.glb", "");
  const std::string text = readFile(studio.scene);
  const Reply before = studio.get("/api/preview?frame=1");
  REQUIRE(before.status == 200);
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"textures/wood.png", "mesh 'textures/wood.png' is not a mesh format sdgbehave reads"},
      {"/etc/passwd", "mesh '/etc/passwd' is not a mesh format sdgbehave reads"},
      {"../../../../etc/passwd", "mesh '../../../../etc/passwd' is not a mesh format sdgbehave reads"},
      {"../outside/crate.glb", "mesh '../outside/crate.glb' is outside the scene's folder and asset roots"},
      {(studio.dir / "outside" / "crate.glb").string(), "is outside the scene's folder and asset roots"},
      {"../../../../../../../../../etc/ssl/x.glb", "is outside the scene's folder and asset roots"},
      {"props/note.glb", "not a binary glTF: it does not start with 'glTF'"},
      {"props/empty.glb", "cannot be read: it is empty"},
      {"props/missing.glb", "mesh 'props/missing.glb' not found"},
  };
  for (const auto& [value, message] : refused) {
    CAPTURE(value);
    Reply r = studio.edit("/World/Crate", {"asset"}, value);
    CHECK(r.status == 400);
    CHECK(r.error().find(message) != std::string::npos);
    // Located at the value in the edited text.
    CHECK(r.error().starts_with(studio.scene.string() + ":6:"));
  }
  CHECK(readFile(studio.scene) == text);
  CHECK(studio.get("/api/diff").body.empty());
  Reply after = studio.get("/api/preview?frame=1");
  CHECK(after.status == 200);
  CHECK(after.body == before.body);
  // A mesh the loader reads is taken, and the preview shows it.
  CHECK(studio.edit("/World/Crate", {"asset"}, "props/crate.obj").status == 200);
  CHECK(studio.get("/api/preview?frame=1").status == 200);
  CHECK(studio.get("/api/diff").body.find("+  /World/Crate: {type: Mesh, asset: \"props/crate.obj\"") != std::string::npos);
}

TEST_CASE("studio server: origins name files one way, absolute", "[studio]") {
  const fs::path cwd = fs::current_path();
  Studio studio("origins");
  // A smart asset below the working folder, which the loader names relative to it.
  fs::create_directories(studio.dir / "scene" / "assets");
  writeFile(studio.dir / "scene" / "assets" / "ball.yaml", "version: 1\nprims:\n  /Ball: {type: Sphere, radius: 0.2}\n");
  writeFile(studio.scene, std::string(kScene) + "  /World/Ball: {reference: assets/ball.yaml, translate: [1, 1, 0]}\n");
  // Started with a relative path: what it prints is absolute all the same.
  fs::current_path(studio.dir);
  StudioOptions options;
  options.scene.scenePath = "scene/scene.yaml";
  ServerOptions serverOptions;
  serverOptions.token = "t0k3n";
  StudioServer relative(options, serverOptions);
  relative.start();
  Reply r = exchange(relative.port(), "GET /api/tree HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(relative.port()) +
                                          "\r\nX-Studio-Token: t0k3n\r\nConnection: close\r\n\r\n");
  fs::current_path(cwd);
  REQUIRE(r.status == 200);
  const Json tree = Json::parse(r.body);
  // Every file an origin names ("FILE:L:C, referenced from FILE:L:C") is absolute.
  auto absolute = [](std::string origin) {
    CAPTURE(origin);
    for (const std::string separator : {", referenced from ", ", from "})
      for (size_t at; (at = origin.find(separator)) != std::string::npos;) origin.replace(at, separator.size(), "\n");
    std::istringstream parts(origin);
    for (std::string part; std::getline(parts, part);)
      if (!part.starts_with("/")) return false;
    return true;
  };
  std::vector<std::string> origins;
  for (const Json& prim : tree["prims"]) {
    origins.push_back(prim["origin"]);
    std::vector<Json> values(prim["attributes"].begin(), prim["attributes"].end());
    for (const Json& b : prim["behaviors"]) values.insert(values.end(), b["variables"].begin(), b["variables"].end());
    for (const Json& a : values)
      if (a["origin"] != "default") origins.push_back(a["origin"]);
  }
  // 6 prims; asset, size, intensity, radius; interval, range:minPosition, range:maxPosition.
  CHECK(origins.size() == 13);
  const std::string asset = (studio.dir / "scene" / "assets" / "ball.yaml").string();
  CHECK(std::count(origins.begin(), origins.end(), asset + ":3:3, referenced from " + studio.scene.string() + ":14:28") == 1);
  for (const std::string& origin : origins) {
    CAPTURE(origin);
    CHECK(absolute(origin));
  }
}

TEST_CASE("studio server: a conflict shows its diff and offers reload or overwrite", "[studio]") {
  Studio studio("conflict");
  REQUIRE(studio.edit("/World/Box", {"size"}, 0.75).status == 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const std::string onDisk = std::string(kScene) + "# changed in an editor\n";
  writeFile(studio.scene, onDisk);
  Json state = Json::parse(studio.get("/api/state").body);
  REQUIRE(state["conflict"] == true);
  // Edits are refused, saying what can be done (and not "save").
  Reply r = studio.edit("/World/Box", {"size"}, 0.8);
  CHECK(r.status == 409);
  CHECK(r.error().find("reload it (dropping the edits here) or overwrite it with the edits here") != std::string::npos);
  CHECK(r.error().find("save or reload") == std::string::npos);
  // The diff is today's: what changed on disk, then what overwriting would write.
  const std::string diff = studio.get("/api/diff").body;
  const std::string path = studio.scene.string();
  CHECK(diff.find("--- " + path + " (as read)\n+++ " + path + " (on disk now)\n") != std::string::npos);
  CHECK(diff.find("+# changed in an editor") != std::string::npos);
  CHECK(diff.find("--- " + path + " (on disk now)\n+++ " + path + " (edited)\n") != std::string::npos);
  CHECK(diff.find("-# changed in an editor") != std::string::npos);
  CHECK(diff.find("+    size: 0.75") != std::string::npos);
  // Save without overwrite is refused and writes nothing; with it, the edits win.
  r = studio.post("/api/save", "{}");
  CHECK(r.status == 409);
  CHECK(r.error().find("reload it (dropping the edits here) or overwrite it (Save, after confirming)") != std::string::npos);
  CHECK(readFile(studio.scene) == onDisk);
  CHECK(studio.post("/api/save", "{\"overwrite\": \"yes\"}").status == 400);
  r = studio.post("/api/save", "{\"overwrite\": true}");
  CHECK(r.status == 200);
  CHECK(readFile(studio.scene).find("    size: 0.75\n") != std::string::npos);
  CHECK(readFile(studio.scene).find("# changed in an editor") == std::string::npos);
  state = Json::parse(studio.get("/api/state").body);
  CHECK(state["conflict"] == false);
  CHECK(state["unsaved"] == false);
  CHECK(studio.edit("/World/Box", {"size"}, 0.8).status == 200);
}

TEST_CASE("studio server: the frame plan is run's, frames_per_iteration and iterations included", "[studio]") {
  Studio studio("frames");
  Json state = Json::parse(studio.get("/api/state").body);
  CHECK(state["frames"] == 2);  // frames_per_iteration, not frames
  CHECK(state["iterations"] == 3);
}
