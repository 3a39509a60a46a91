#pragma once
// The studio's HTTP server (docs/studio.md, "HTTP API"): the front end's
// files, and per film its details, video (with Range requests, or an H.264
// proxy), thumbnails, level-of-detail curves, raw track samples, edits
// (GET, and PUT with a stale-revision check and a re-render), exports and
// background jobs. Guards in http_security.h.
//
//   std::vector<std::unique_ptr<FilmSession>> films = ...;
//   StudioServer server(std::move(films), options);
//   int port = server.Bind();   // port 0: any free port
//   server.Serve();             // until Stop() (or on a thread: Start())

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "studio/film_session.h"
#include "studio/jobs.h"
#include "studio/web_files.h"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace hapcine::studio {

constexpr size_t kMaxBodyBytes = 4 << 20;  // 4 MiB: larger bodies get 413

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8787;     // 0: any free port
  std::string token;   // non-empty: every request must carry it
  WebFiles web = WebFiles::Embedded();
  int thumbnail_width = 320;
};

class StudioServer {
 public:
  StudioServer(std::vector<std::unique_ptr<FilmSession>> films, ServerOptions options);
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  // Binds host:port; returns the port. Throws hapcine::Error when it cannot.
  int Bind();
  // Serves on this thread until Stop().
  void Serve();
  // Bind() and Serve() on a thread of its own; returns the port.
  int Start();
  void Stop();

  // "http://127.0.0.1:8787/" (+ "?token=..." when a token is required).
  std::string Url() const;

 private:
  void AddRoutes();
  bool Guard(const httplib::Request& req, httplib::Response& res) const;
  FilmSession& FilmOf(const httplib::Request& req) const;  // throws HttpError 404
  void ServeFile(const httplib::Request& req, httplib::Response& res, const std::string& path,
                 const std::string& content_type) const;
  void Export(const httplib::Request& req, httplib::Response& res);
  void Proxy(const httplib::Request& req, httplib::Response& res);
  void Thumbnail(const httplib::Request& req, httplib::Response& res);

  std::vector<std::unique_ptr<FilmSession>> films_;
  ServerOptions options_;
  std::unique_ptr<httplib::Server> http_;
  JobRegistry jobs_;
  std::mutex thumbnail_mu_;  // one ffmpeg at a time for thumbnails
  std::thread thread_;
  int port_ = 0;
};

}  // namespace hapcine::studio
