// `hapcine studio` as a user runs it: one-line errors, the printed URL, the
// token with --host, and Ctrl-C (SIGINT) stopping it cleanly.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <regex>
#include <thread>

// Eigen (through the test film) before httplib.h: the <resolv.h> it pulls in
// defines `_res`, a parameter name inside Eigen's headers.
#include "studio/test_film_for_test.h"
#include "testpaths/test_paths.h"
#include "tests/run_hapcine.h"

#include <httplib.h>

namespace {
namespace fs = std::filesystem;
using hapcine::testing::StudioTestFilm;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::Slurp;

TEST(StudioCli, ABadFilmIsOneLineNamingItAndExit1) {
  StudioTestFilm film;
  const fs::path missing = fs::path(film.dir()) / "missing.mp4";
  const auto r = RunHapcine("studio " + Quote(missing) + " -q", film.dir());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine studio: " + missing.string() + ": no such file\n");
  const auto usage = RunHapcine("studio " + Quote(film.film()) + " --washout off", film.dir());
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_NE(usage.err.find("--washout is a haptics option"), std::string::npos) << usage.err;
}

// Starts `hapcine studio ARGS` in the background; returns its pid and the
// URL it prints (empty if none within 60 s).
std::pair<pid_t, std::string> StartStudio(const std::string& args, const StudioTestFilm& film) {
  const fs::path out = fs::path(film.dir()) / "studio_out.txt";
  const fs::path err = fs::path(film.dir()) / "studio_err.txt";
  const std::string cmd = std::string("'") + HAPCINE_EXE + "' studio " + args + " </dev/null >'" +
                          out.string() + "' 2>'" + err.string() + "' & echo $!";
  FILE* pipe = popen(cmd.c_str(), "r");
  pid_t pid = 0;
  if (!pipe || fscanf(pipe, "%d", &pid) != 1) pid = 0;
  if (pipe) pclose(pipe);
  const std::regex url_re("(http://[^ \\n]*)");
  for (int i = 0; i < 600 && pid > 0; ++i) {
    std::smatch m;
    const std::string text = Slurp(out);
    if (std::regex_search(text, m, url_re)) return {pid, m[1]};
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return {pid, ""};
}

bool StopsWithin(pid_t pid, double seconds) {
  for (int i = 0; i < seconds * 20; ++i) {
    if (kill(pid, 0) != 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

int PortOf(const std::string& url) {
  std::smatch m;
  const std::regex port_re(":([0-9]+)/");
  return std::regex_search(url, m, port_re) ? std::stoi(m[1]) : 0;
}

TEST(StudioCli, ServesOnLoopbackAndStopsOnSigint) {
  StudioTestFilm film;
  const auto [pid, url] = StartStudio(Quote(film.film()) + " --camera " + Quote(film.camera()) +
                                          " --port 0", film);
  ASSERT_GT(pid, 0);
  ASSERT_FALSE(url.empty()) << Slurp(fs::path(film.dir()) / "studio_err.txt");
  EXPECT_EQ(url.rfind("http://127.0.0.1:", 0), 0u) << url;
  EXPECT_EQ(url.find("token"), std::string::npos);
  httplib::Client client("127.0.0.1", PortOf(url));
  auto films = client.Get("/api/films");
  ASSERT_TRUE(films);
  EXPECT_EQ(films->status, 200);
  EXPECT_NE(films->body.find("\"film.mp4\""), std::string::npos);
  kill(pid, SIGINT);
  EXPECT_TRUE(StopsWithin(pid, 10));
  EXPECT_NE(Slurp(fs::path(film.dir()) / "studio_err.txt").find("hapcine studio: stopped"),
            std::string::npos);
}

TEST(StudioCli, AnotherHostNeedsThePrintedToken) {
  StudioTestFilm film;
  const auto [pid, url] = StartStudio(Quote(film.film()) + " --camera " + Quote(film.camera()) +
                                          " --port 0 --host 0.0.0.0", film);
  ASSERT_GT(pid, 0);
  ASSERT_FALSE(url.empty()) << Slurp(fs::path(film.dir()) / "studio_err.txt");
  const size_t at = url.find("?token=");
  ASSERT_NE(at, std::string::npos) << url;
  const std::string token = url.substr(at + 7);
  EXPECT_EQ(token.size(), 32u);
  httplib::Client client("127.0.0.1", PortOf(url));
  EXPECT_EQ(client.Get("/api/films")->status, 401);
  EXPECT_EQ(client.Get(("/api/films?token=" + token).c_str())->status, 200);
  kill(pid, SIGTERM);
  EXPECT_TRUE(StopsWithin(pid, 10));
}

}  // namespace
