// HTTP tests against a server started in-process on 127.0.0.1, port 0.
#include "studio/studio_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/haptic_track.h"
#include "studio/http_security.h"
#include "studio/test_film_for_test.h"

namespace hapcine::studio {
namespace {
namespace fs = std::filesystem;
using hapcine::testing::FilmByte;
using hapcine::testing::StudioTestFilm;

const char kEditsGainZeroInShot1[] =
    R"({"format":"hapcine-edits","version":1,"revision":REV,"shots":[{"shot":1,"gain":0}]})";

std::string EditsBody(int revision) {
  std::string body = kEditsGainZeroInShot1;
  body.replace(body.find("REV"), 3, std::to_string(revision));
  return body;
}

class StudioServerTest : public ::testing::Test {
 protected:
  void Start(ServerOptions options = {}, std::string film = "") {
    std::vector<std::unique_ptr<FilmSession>> films;
    films.push_back(std::make_unique<FilmSession>("f0", film.empty() ? film_.film() : film,
                                                  film_.camera(), HapticOptions{}));
    options.host = "127.0.0.1";
    options.port = 0;
    server_ = std::make_unique<StudioServer>(std::move(films), std::move(options));
    port_ = server_->Start();
  }
  void SetUp() override {}
  void TearDown() override {
    if (server_) server_->Stop();
  }
  httplib::Client Client() const { return httplib::Client("127.0.0.1", port_); }
  nlohmann::json GetJson(const std::string& path, int expected_status = 200) {
    auto res = Client().Get(path.c_str());
    EXPECT_TRUE(res) << path;
    if (!res) return nullptr;
    EXPECT_EQ(res->status, expected_status) << path << ": " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/json") << path;
    return nlohmann::json::parse(res->body);
  }
  httplib::Result PutEdits(const std::string& body) {
    return Client().Put("/api/films/f0/edits", body, "application/json");
  }

  StudioTestFilm film_;
  std::unique_ptr<StudioServer> server_;
  int port_ = 0;
};

TEST_F(StudioServerTest, ListsFilmsAndTheirDetails) {
  Start();
  const nlohmann::json films = GetJson("/api/films");
  ASSERT_EQ(films.size(), 1u);
  EXPECT_EQ(films[0]["id"], "f0");
  EXPECT_EQ(films[0]["name"], "film.mp4");
  EXPECT_EQ(films[0]["shots"], 2);
  EXPECT_EQ(films[0]["width"], 640);
  const nlohmann::json d = GetJson("/api/films/f0");
  EXPECT_EQ(d["revision"], 0);
  EXPECT_EQ(d["video_url"], "/api/films/f0/video");
  ASSERT_EQ(d["shots"].size(), 2u);
  EXPECT_EQ(d["shots"][1]["shot"], 1);
  EXPECT_NEAR(d["shots"][1]["start_s"].get<double>(), 7.0 + 1.0 / 30, 1e-5);
  EXPECT_EQ(d["shots"][1]["thumbnail_url"], "/api/films/f0/thumbnails/1.jpg");
  EXPECT_EQ(d["shots"][0]["washout"]["mode"], "adaptive");
  EXPECT_TRUE(d["effects"].is_array());
  EXPECT_TRUE(d["seat"].contains("workspace_half_m")) << d["seat"].dump();
  const nlohmann::json missing = GetJson("/api/films/f9", 404);
  EXPECT_EQ(missing["error"], "no film 'f9'");
}

TEST_F(StudioServerTest, StaticFilesNeverLeaveTheFrontEnd) {
  ServerOptions options;
  options.web = WebFiles::FromList({{"index.html", "<p>studio</p>"}, {"app.js", "export {};"}});
  Start(options);
  auto index = Client().Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->body, "<p>studio</p>");
  auto app = Client().Get("/static/app.js");
  ASSERT_TRUE(app);
  EXPECT_EQ(app->status, 200);
  EXPECT_EQ(app->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  for (const char* path : {"/static/../../etc/passwd", "/static/%2e%2e/%2e%2e/etc/passwd",
                           "/static/..%2f..%2fetc%2fpasswd", "/static//etc/passwd",
                           "/static/%2fetc%2fpasswd", "/static/.hidden", "/../../etc/passwd",
                           "/static/app.js%00.png"}) {
    auto res = Client().Get(path);
    ASSERT_TRUE(res) << path;
    EXPECT_GE(res->status, 400) << path;
    EXPECT_EQ(res->body.find("root:"), std::string::npos) << path;
  }
}

TEST_F(StudioServerTest, WebFolderSymlinksCannotEscape) {
  const fs::path web = fs::path(film_.dir()) / "web";
  fs::create_directories(web);
  std::ofstream(web / "index.html") << "<p>from disk</p>";
  std::ofstream(fs::path(film_.dir()) / "outside.txt") << "outside";
  fs::create_symlink(fs::path(film_.dir()) / "outside.txt", web / "leak.txt");
  fs::create_symlink("/etc/passwd", web / "passwd.txt");
  ServerOptions options;
  options.web = WebFiles::Directory(web.string());
  Start(options);
  EXPECT_EQ(Client().Get("/")->body, "<p>from disk</p>");
  for (const char* path : {"/static/leak.txt", "/static/passwd.txt"}) {
    auto res = Client().Get(path);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 404) << path;
    EXPECT_EQ(res->body.find("outside"), std::string::npos);
  }
}

TEST_F(StudioServerTest, WithoutAFrontEndTheIndexIsAPlaceholder) {
  ServerOptions options;
  options.web = WebFiles::FromList({});
  Start(options);
  auto res = Client().Get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_NE(res->body.find("/api/films"), std::string::npos);
}

TEST_F(StudioServerTest, VideoAnswersRangeRequests) {
  Start();
  httplib::Client client = Client();
  auto whole = client.Get("/api/films/f0/video");
  ASSERT_TRUE(whole);
  EXPECT_EQ(whole->status, 200);
  EXPECT_EQ(whole->body.size(), 300000u);
  EXPECT_EQ(whole->get_header_value("Accept-Ranges"), "bytes");
  auto part = client.Get("/api/films/f0/video", {{"Range", "bytes=1000-1999"}});
  ASSERT_TRUE(part);
  EXPECT_EQ(part->status, 206);
  EXPECT_EQ(part->get_header_value("Content-Range"), "bytes 1000-1999/300000");
  ASSERT_EQ(part->body.size(), 1000u);
  for (size_t i = 0; i < 1000; ++i) ASSERT_EQ(part->body[i], FilmByte(1000 + i)) << i;
  auto tail = client.Get("/api/films/f0/video", {{"Range", "bytes=299990-"}});
  ASSERT_TRUE(tail);
  EXPECT_EQ(tail->status, 206);
  ASSERT_EQ(tail->body.size(), 10u);
  EXPECT_EQ(tail->body[9], FilmByte(299999));
  auto over = client.Get("/api/films/f0/video", {{"Range", "bytes=299000-400000"}});
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 206);
  EXPECT_EQ(over->get_header_value("Content-Range"), "bytes 299000-299999/300000");
  EXPECT_EQ(over->body.size(), 1000u);
  auto past = client.Get("/api/films/f0/video", {{"Range", "bytes=400000-400010"}});
  ASSERT_TRUE(past);
  EXPECT_EQ(past->status, 416);
  EXPECT_EQ(past->get_header_value("Content-Range"), "bytes */300000");
}

TEST_F(StudioServerTest, OversizedAndMalformedBodiesAreRefused) {
  Start();
  auto big = PutEdits(std::string(kMaxBodyBytes + 1, ' '));
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  for (const std::string body : {"{not json", "", "[]", "{\"format\":\"hapcine-edits\",\"version\":1,\"gian\":2}",
                                 "{\"format\":\"hapcine-edits\",\"version\":1,\"shots\":[{\"shot\":7}]}",
                                 "{\"format\":\"hapcine-edits\",\"version\":1,\"shots\":[{\"shot\":0,\"gain\":1e999}]}"}) {
    auto res = PutEdits(body);
    ASSERT_TRUE(res) << body;
    EXPECT_EQ(res->status, 400) << body << ": " << res->body;
    const nlohmann::json error = nlohmann::json::parse(res->body);
    EXPECT_FALSE(error["error"].get<std::string>().empty());
  }
  auto bad_export = Client().Post("/api/films/f0/export", "{\"kind\": 3", "application/json");
  ASSERT_TRUE(bad_export);
  EXPECT_EQ(bad_export->status, 400);
  EXPECT_FALSE(fs::exists(film_.edits()));
  EXPECT_EQ(GetJson("/api/films/f0")["revision"], 0);  // still serving
}

TEST_F(StudioServerTest, SaveRerendersTheTrackAndRefusesAStaleRevision) {
  Start();
  const nlohmann::json before = GetJson("/api/films/f0/track?from=0&to=14");
  auto saved = PutEdits(EditsBody(0));
  ASSERT_TRUE(saved);
  ASSERT_EQ(saved->status, 200) << saved->body;
  EXPECT_EQ(nlohmann::json::parse(saved->body)["revision"], 1);
  ASSERT_TRUE(fs::exists(film_.edits()));
  EXPECT_EQ(GetJson("/api/films/f0/edits")["revision"], 1);
  EXPECT_EQ(GetJson("/api/films/f0")["shots"][1]["gain"], 0.0);
  const nlohmann::json after = GetJson("/api/films/f0/track?from=0&to=14");
  ASSERT_EQ(before["t"].size(), after["t"].size());
  double moved_before = 0;
  for (size_t i = 0; i < after["t"].size(); ++i) {
    const double t = after["t"][i];
    if (t < 6.5) {  // shot 0, before the cut's ramp
      EXPECT_EQ(after["head"][i], before["head"][i]) << t;
    }
    if (t > 8.5) {  // shot 1 after the ramp: silent
      for (int k = 0; k < 3; ++k) EXPECT_EQ(after["head"][i][k], 0.0) << t;
      moved_before += std::abs(before["head"][i][1].get<double>());
    }
  }
  EXPECT_GT(moved_before, 1.0);  // the crane shot moved before the edit
  auto stale = PutEdits(EditsBody(0));
  ASSERT_TRUE(stale);
  EXPECT_EQ(stale->status, 409);
  EXPECT_EQ(nlohmann::json::parse(stale->body)["revision"], 1);
}

TEST_F(StudioServerTest, OfTwoSavesOnTheSameRevisionExactlyOneWins) {
  Start();
  int status[2] = {0, 0};
  std::thread a([&] { status[0] = PutEdits(EditsBody(0))->status; });
  std::thread b([&] { status[1] = PutEdits(EditsBody(0))->status; });
  a.join();
  b.join();
  EXPECT_EQ(std::min(status[0], status[1]), 200);
  EXPECT_EQ(std::max(status[0], status[1]), 409);
  EXPECT_EQ(GetJson("/api/films/f0/edits")["revision"], 1);
}

TEST_F(StudioServerTest, ATokenIsRequiredWhenSet) {
  ServerOptions options;
  options.token = NewToken();
  Start(options);
  EXPECT_EQ(Client().Get("/api/films")->status, 401);
  EXPECT_EQ(Client().Get("/")->status, 401);
  EXPECT_EQ(Client().Get("/api/films?token=0123")->status, 401);
  auto first = Client().Get(("/?token=" + options.token).c_str());
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 200);
  EXPECT_NE(first->get_header_value("Set-Cookie").find("hapcine_token=" + options.token),
            std::string::npos);
  EXPECT_EQ(Client().Get("/api/films", {{"Cookie", "hapcine_token=" + options.token}})->status, 200);
  EXPECT_EQ(Client().Get("/api/films", {{"Authorization", "Bearer " + options.token}})->status, 200);
  EXPECT_EQ(Client().Get("/api/films", {{"Authorization", "Bearer x" + options.token}})->status, 401);
}

TEST_F(StudioServerTest, ForeignHostsAndOriginsAreRefused) {
  Start();
  EXPECT_EQ(Client().Get("/api/films", {{"Host", "evil.example:8787"}})->status, 403);
  httplib::Headers foreign = {{"Origin", "http://evil.example"}};
  EXPECT_EQ(Client().Put("/api/films/f0/edits", foreign, EditsBody(0), "application/json")->status, 403);
  EXPECT_FALSE(fs::exists(film_.edits()));
}

TEST_F(StudioServerTest, CurvesAndTrackRangesAreChecked) {
  Start();
  const nlohmann::json curves = GetJson("/api/films/f0/curves?points=50");
  EXPECT_LE(curves["t"].size(), 50u);
  EXPECT_EQ(curves["series"].size(), 17u);
  for (const char* name : {"pan", "tilt", "roll", "fov", "tx", "ty", "tz", "confidence", "head_x",
                           "left_y", "right_z"}) {
    EXPECT_EQ(curves["series"][name]["max"].size(), curves["t"].size()) << name;
  }
  const nlohmann::json zoomed = GetJson("/api/films/f0/curves?from=2&to=3&points=20000");
  EXPECT_EQ(zoomed["t"].size(), 101u);  // the track's samples in [2, 3] at 100 Hz
  GetJson("/api/films/f0/curves?points=0", 400);
  GetJson("/api/films/f0/curves?points=20001", 400);
  GetJson("/api/films/f0/curves?from=abc", 400);
  GetJson("/api/films/f0/curves?from=5&to=1", 400);
  GetJson("/api/films/f0/track?from=3&to=1", 400);
  const nlohmann::json capped = GetJson("/api/films/f0/track?from=0&to=1000");
  EXPECT_LE(capped["t"].back().get<double>(), 14.1);  // the whole film: under 60 s
  const nlohmann::json track = GetJson("/api/films/f0/track?from=1&to=2");
  EXPECT_EQ(track["rate_hz"], 100.0);
  EXPECT_EQ(track["t"].size(), 101u);
  EXPECT_EQ(track["head"][0].size(), 3u);
}

TEST_F(StudioServerTest, ExportsWriteBesideTheFilm) {
  Start();
  auto res = Client().Post("/api/films/f0/export", R"({"kind":"haptic"})", "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const std::string path = nlohmann::json::parse(res->body)["path"];
  EXPECT_EQ(path, (fs::path(film_.dir()) / "film.haptic.csv").string());
  EXPECT_NEAR(ReadHapticTrackFile(path).duration_s(), 14.0, 0.05);
  auto hjif = Client().Post("/api/films/f0/export", R"({"kind":"hjif"})", "application/json");
  ASSERT_TRUE(hjif);
  EXPECT_EQ(hjif->status, 200) << hjif->body;
  EXPECT_TRUE(fs::exists(fs::path(film_.dir()) / "film.hjif"));
  auto bogus = Client().Post("/api/films/f0/export", R"({"kind":"wav"})", "application/json");
  ASSERT_TRUE(bogus);
  EXPECT_EQ(bogus->status, 400);
  GetJson("/api/jobs/j99", 404);
}

// A real clip a browser cannot play (MPEG-4 Part 2 in AVI, made by ffmpeg):
// the server points at a proxy, answers 202 with progress while ffmpeg makes
// it, then serves an MP4; and a thumbnail of a shot.
TEST_F(StudioServerTest, AnUnplayableCodecGetsAnH264ProxyAndThumbnails) {
  const std::string avi = film_.dir() + "/clip.avi";
  const std::string make = "ffmpeg -nostdin -loglevel error -f lavfi -i testsrc=size=64x48:rate=5:duration=8 "
                           "-c:v mpeg4 " + avi;
  if (std::system(make.c_str()) != 0) GTEST_SKIP() << "ffmpeg cannot make the test clip";
  Start({}, avi);
  EXPECT_EQ(GetJson("/api/films/f0")["video_url"], "/api/films/f0/proxy.mp4");
  httplib::Response proxy;
  bool saw_202 = false;
  for (int i = 0; i < 600; ++i) {
    auto res = Client().Get("/api/films/f0/proxy.mp4");
    ASSERT_TRUE(res);
    proxy = *res;
    if (proxy.status != 202) break;
    saw_202 = true;
    EXPECT_TRUE(nlohmann::json::parse(proxy.body).contains("progress"));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(saw_202);
  ASSERT_EQ(proxy.status, 200) << proxy.body;
  EXPECT_EQ(proxy.get_header_value("Content-Type"), "video/mp4");
  ASSERT_GT(proxy.body.size(), 8u);
  EXPECT_EQ(proxy.body.substr(4, 4), "ftyp");
  auto thumb = Client().Get("/api/films/f0/thumbnails/0.jpg");
  ASSERT_TRUE(thumb);
  ASSERT_EQ(thumb->status, 200) << thumb->body;
  EXPECT_EQ(thumb->body.substr(0, 2), "\xff\xd8");
  // Shot 1 lies past the clip's end: the first frame stands in.
  EXPECT_EQ(Client().Get("/api/films/f0/thumbnails/1.jpg")->status, 200);
  EXPECT_EQ(Client().Get("/api/films/f0/thumbnails/7.jpg")->status, 404);
  EXPECT_EQ(Client().Get("/api/films/f0/video")->status, 200);  // the original stays reachable
}

}  // namespace
}  // namespace hapcine::studio
