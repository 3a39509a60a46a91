#include "studio/studio_server.h"  // first: Eigen before httplib.h

// httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's headers
// when they come after it.
#include <httplib.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/error_message.h"
#include "datasets/preview.h"
#include "haptics/hjif_export.h"
#include "studio/http_security.h"

namespace hapcine::studio {
namespace {
namespace fs = std::filesystem;

constexpr int kDefaultCurvePoints = 2000;
constexpr int kMaxCurvePoints = 20000;
constexpr size_t kFileChunkBytes = 256 * 1024;
const char kJson[] = "application/json";

void SendJson(httplib::Response& res, const nlohmann::json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(), kJson);
}

void SendError(httplib::Response& res, int status, const std::string& message,
               const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json body = extra.is_object() ? extra : nlohmann::json::object();
  body["error"] = message;
  res.status = status;
  res.set_content(body.dump(), kJson);
}

using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

// Every answer of a handler that fails is a JSON error: 4xx for what the
// request got wrong (HttpError), 500 for the rest, never a crash.
httplib::Server::Handler Guarded(Handler handler) {
  return [handler = std::move(handler)](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
    } catch (const HttpError& e) {
      SendError(res, e.status, e.message, e.extra);
    } catch (...) {
      SendError(res, 500, EscapedExceptionMessage(std::current_exception()));
    }
  };
}

// A finite number from the query, or `fallback` when absent.
double QueryNumber(const httplib::Request& req, const std::string& key, double fallback) {
  if (!req.has_param(key.c_str())) return fallback;
  const std::string text = req.get_param_value(key.c_str());
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (...) {
  }
  throw HttpError{400, key + ": not a number: '" + text.substr(0, 40) + "'"};
}

// Byte ranges [first, last] of a Range header (-1: absent) made explicit
// and cut to the file; false when one starts past the end or is empty.
bool ClampRanges(httplib::Ranges& ranges, size_t size) {
  const auto n = static_cast<ssize_t>(size);
  for (auto& [first, last] : ranges) {
    if (first < 0) {  // "bytes=-N": the last N bytes
      if (last <= 0) return false;
      first = std::max<ssize_t>(0, n - last);
      last = n - 1;
    } else {
      if (first >= n || (last >= 0 && last < first)) return false;
      last = last < 0 ? n - 1 : std::min(last, n - 1);
    }
  }
  return true;
}

nlohmann::json ParseJsonBody(const std::string& body) {
  try {
    return nlohmann::json::parse(body);
  } catch (const nlohmann::json::parse_error& e) {
    throw HttpError{400, std::string("malformed JSON: ") + e.what()};
  }
}

}  // namespace

StudioServer::StudioServer(std::vector<std::unique_ptr<FilmSession>> films, ServerOptions options)
    : films_(std::move(films)), options_(std::move(options)),
      http_(std::make_unique<httplib::Server>()) {
  http_->set_payload_max_length(kMaxBodyBytes);
  // httplib's own errors (413, 404 without a route, ...) as JSON too.
  http_->set_error_handler(httplib::Server::HandlerWithResponse(
      [](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    const std::string message = res.status == 413 ? "request body over 4 MiB"
                                : res.status == 404 ? "not found"
                                : res.status == 416 ? "range not satisfiable"
                                                    : "HTTP status " + std::to_string(res.status);
    SendError(res, res.status, message);
    return httplib::Server::HandlerResponse::Handled;
  }));
  http_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return Guard(req, res) ? httplib::Server::HandlerResponse::Unhandled
                           : httplib::Server::HandlerResponse::Handled;
  });
  AddRoutes();
}

StudioServer::~StudioServer() { Stop(); }

bool StudioServer::Guard(const httplib::Request& req, httplib::Response& res) const {
  const std::string host = req.get_header_value("Host");
  if (options_.token.empty()) {
    // Loopback only: a page of another site reaching us through DNS
    // rebinding names its own host.
    if (!host.empty() && !IsLoopbackHost(HostWithoutPort(host))) {
      SendError(res, 403, "Host '" + host + "' is not this server");
      return false;
    }
  } else {
    const std::string query = req.has_param("token") ? req.get_param_value("token") : "";
    const std::string given = RequestToken(query, req.get_header_value("Cookie"),
                                           req.get_header_value("Authorization"));
    if (!TokensEqual(options_.token, given)) {
      SendError(res, 401, "a token is required: open the URL printed by hapcine studio");
      return false;
    }
    if (!query.empty())
      res.set_header("Set-Cookie", std::string(kTokenCookie) + "=" + options_.token +
                                       "; Path=/; HttpOnly; SameSite=Strict");
  }
  // Changes only from pages of this server (a form elsewhere cannot post here).
  const std::string origin = req.get_header_value("Origin");
  if (req.method != "GET" && req.method != "HEAD" && !origin.empty() &&
      origin != "http://" + host) {
    SendError(res, 403, "Origin '" + origin + "' is not this server");
    return false;
  }
  return true;
}

FilmSession& StudioServer::FilmOf(const httplib::Request& req) const {
  const std::string id = req.matches[1];
  for (const auto& f : films_) {
    if (f->id() == id) return *f;
  }
  throw HttpError{404, "no film '" + id.substr(0, 40) + "'"};
}

void StudioServer::ServeFile(const httplib::Request& req, httplib::Response& res,
                             const std::string& path, const std::string& content_type) const {
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) throw HttpError{404, "cannot read " + fs::path(path).filename().string()};
  // httplib 0.11 neither refuses nor clamps a range past the end; the
  // request is this server's own object, so the ranges are fixed in place.
  if (!ClampRanges(const_cast<httplib::Request&>(req).ranges, static_cast<size_t>(size))) {
    res.set_header("Content-Range", "bytes */" + std::to_string(size));
    throw HttpError{416, "range not satisfiable (the file has " + std::to_string(size) + " bytes)"};
  }
  res.set_header("Accept-Ranges", "bytes");
  res.set_header("Cache-Control", "no-cache");
  // httplib cuts the provider's bytes to the request's Range (206).
  res.set_content_provider(
      static_cast<size_t>(size), content_type,
      [path](size_t offset, size_t length, httplib::DataSink& sink) {
        std::ifstream in(path, std::ios::binary);
        in.seekg(static_cast<std::streamoff>(offset));
        std::vector<char> buffer(std::min(length, kFileChunkBytes));
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const std::streamsize got = in.gcount();
        if (got <= 0) return false;
        return sink.write(buffer.data(), static_cast<size_t>(got));
      });
}

void StudioServer::AddRoutes() {
  httplib::Server& s = *http_;
  s.Get("/", Guarded([this](const httplib::Request&, httplib::Response& res) {
    const WebFile index = options_.web.Index();
    res.set_content(index.body, index.content_type.c_str());
  }));
  s.Get(R"(/static/(.+))", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    const auto file = options_.web.Find(req.matches[1]);
    if (!file) throw HttpError{404, "no front-end file '" + std::string(req.matches[1]).substr(0, 80) + "'"};
    res.set_content(file->body, file->content_type.c_str());
  }));
  s.Get("/api/films", Guarded([this](const httplib::Request&, httplib::Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& f : films_) list.push_back(f->Summary());
    SendJson(res, list);
  }));
  s.Get(R"(/api/films/([^/]+))", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    SendJson(res, FilmOf(req).Details());
  }));
  s.Get(R"(/api/films/([^/]+)/video)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    const FilmSession& film = FilmOf(req);
    ServeFile(req, res, film.film(), "video/" + std::string(film.media().container.find("webm") != std::string::npos ? "webm" : "mp4"));
  }));
  s.Get(R"(/api/films/([^/]+)/proxy\.mp4)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    Proxy(req, res);
  }));
  s.Get(R"(/api/films/([^/]+)/thumbnails/(\d{1,9})\.jpg)",
        Guarded([this](const httplib::Request& req, httplib::Response& res) { Thumbnail(req, res); }));
  s.Get(R"(/api/films/([^/]+)/curves)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    const FilmSession& film = FilmOf(req);
    const double from = QueryNumber(req, "from", 0.0);
    const double to = QueryNumber(req, "to", film.duration_s());
    const double points = QueryNumber(req, "points", kDefaultCurvePoints);
    if (to < from) throw HttpError{400, "to must not be before from"};
    if (points < 1 || points > kMaxCurvePoints)
      throw HttpError{400, "points must be in [1, " + std::to_string(kMaxCurvePoints) + "]"};
    res.set_content(film.CurvesJson(from, to, static_cast<int>(points)), kJson);
  }));
  s.Get(R"(/api/films/([^/]+)/track)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    const FilmSession& film = FilmOf(req);
    const double from = QueryNumber(req, "from", 0.0);
    const double to = QueryNumber(req, "to", std::min(film.duration_s(), from + 60.0));
    SendJson(res, film.TrackJson(from, to));
  }));
  s.Get(R"(/api/films/([^/]+)/edits)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    res.set_content(FilmOf(req).EditsJson(), kJson);
  }));
  s.Put(R"(/api/films/([^/]+)/edits)", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    SendJson(res, FilmOf(req).SaveEdits(req.body));
  }));
  s.Post(R"(/api/films/([^/]+)/export)",
         Guarded([this](const httplib::Request& req, httplib::Response& res) { Export(req, res); }));
  s.Get(R"(/api/jobs/([^/]+))", Guarded([this](const httplib::Request& req, httplib::Response& res) {
    const auto status = jobs_.Status(req.matches[1]);
    if (!status) throw HttpError{404, "no job '" + std::string(req.matches[1]).substr(0, 40) + "'"};
    SendJson(res, status->ToJson());
  }));
}

void StudioServer::Export(const httplib::Request& req, httplib::Response& res) {
  FilmSession& film = FilmOf(req);
  const nlohmann::json body = ParseJsonBody(req.body);
  if (!body.is_object() || !body.contains("kind") || !body["kind"].is_string())
    throw HttpError{400, "the body must be {\"kind\": \"haptic\"|\"hjif\"|\"preview\"}"};
  const std::string kind = body["kind"];
  const std::shared_ptr<const HapticTrack> track = film.track();
  if (kind == "haptic") {
    const std::string path = film.OutputPath("haptic.csv");
    WriteHapticTrackFile(*track, path);
    SendJson(res, {{"path", path}});
  } else if (kind == "hjif") {
    const std::string path = film.OutputPath("hjif");
    HjifOptions hjif;
    hjif.gain_m = film.options().seat.workspace_half_m;
    hjif.description = fs::path(path).stem().string();
    WriteHjifFile(*track, path, hjif);
    SendJson(res, {{"path", path}});
  } else if (kind == "preview") {
    const std::string job = jobs_.Start([&film, track](const JobProgressFn& progress) {
      fs::create_directories(film.CacheDir());
      PreviewOptions preview;
      preview.video = film.film();
      preview.track = (fs::path(film.CacheDir()) / (fs::path(film.film()).stem().string() + ".studio.haptic.csv")).string();
      WriteHapticTrackFile(*track, preview.track);
      preview.output = film.OutputPath("preview.mp4");
      preview.Check();
      RenderPreview(preview, [&](int done, int total) {
        if (total > 0) progress(static_cast<double>(done) / total);
      });
      return preview.output;
    });
    SendJson(res, {{"job", job}});
  } else {
    throw HttpError{400, "kind: '" + kind.substr(0, 40) + "' is not haptic, hjif or preview"};
  }
}

void StudioServer::Proxy(const httplib::Request& req, httplib::Response& res) {
  FilmSession& film = FilmOf(req);
  if (film.media().browser_playable) throw HttpError{404, "this film plays as it is: use /video"};
  const std::string path =
      (fs::path(film.CacheDir()) / (fs::path(film.film()).stem().string() + ".proxy.mp4")).string();
  std::error_code ec;
  if (fs::exists(path, ec) && fs::last_write_time(path, ec) >= fs::last_write_time(film.film(), ec)) {
    ServeFile(req, res, path, "video/mp4");
    return;
  }
  const std::string job = jobs_.StartOnce("proxy:" + film.id(), [&film, path](const JobProgressFn& progress) {
    fs::create_directories(film.CacheDir());
    MakeProxy(film.film(), film.media().duration_s > 0 ? film.media().duration_s : film.duration_s(),
              path, progress);
    return path;
  });
  const JobStatus status = *jobs_.Status(job);
  if (status.state == JobState::kFailed) throw HttpError{500, "the proxy failed: " + status.error};
  if (status.state == JobState::kDone) {
    ServeFile(req, res, path, "video/mp4");
    return;
  }
  nlohmann::json body = status.ToJson();
  body["job"] = job;
  SendJson(res, body, 202);
}

void StudioServer::Thumbnail(const httplib::Request& req, httplib::Response& res) {
  FilmSession& film = FilmOf(req);
  const int shot = std::stoi(std::string(req.matches[2]));
  const ShotSpan* span = nullptr;
  for (const ShotSpan& s : film.shots()) {
    if (s.shot == shot) span = &s;
  }
  if (!span) throw HttpError{404, "no shot " + std::to_string(shot)};
  const std::string path = (fs::path(film.CacheDir()) / (fs::path(film.film()).stem().string() +
                                                         ".shot" + std::to_string(shot) + ".jpg"))
                               .string();
  {
    std::lock_guard<std::mutex> lock(thumbnail_mu_);
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      fs::create_directories(film.CacheDir());
      MakeThumbnail(film.film(), 0.5 * (span->start_s + span->end_s), options_.thumbnail_width, path);
    }
  }
  ServeFile(req, res, path, "image/jpeg");
}

int StudioServer::Bind() {
  if (options_.port == 0) {
    port_ = http_->bind_to_any_port(options_.host);
  } else {
    port_ = http_->bind_to_port(options_.host, options_.port) ? options_.port : -1;
  }
  if (port_ <= 0)
    throw Error(options_.host + ":" + std::to_string(options_.port),
                "cannot listen there (in use? try another --port)");
  return port_;
}

void StudioServer::Serve() { http_->listen_after_bind(); }

int StudioServer::Start() {
  const int port = Bind();
  thread_ = std::thread([this] { Serve(); });
  while (!http_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return port;
}

void StudioServer::Stop() {
  if (http_) http_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string StudioServer::Url() const {
  std::string host = options_.host;
  // Every address: name the machine, which others can reach.
  if (host == "0.0.0.0" || host == "::") {
    char name[256] = {0};
    host = gethostname(name, sizeof name - 1) == 0 && name[0] ? name : host;
  }
  const bool v6 = host.find(':') != std::string::npos;
  std::string url = "http://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port_) + "/";
  if (!options_.token.empty()) url += "?token=" + options_.token;
  return url;
}

}  // namespace hapcine::studio
