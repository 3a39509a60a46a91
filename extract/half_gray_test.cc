#include "extract/half_gray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

extern "C" {
#include <libswscale/swscale.h>
}

namespace hapcine {
namespace {

// A luma plane of `kind`: 0 random bytes (every value, clipping at both
// ends), 1 a smooth gradient with fine stripes (the usual picture), 2 the
// limited-range extremes only (16 / 235, and below / above them).
std::vector<uint8_t> Luma(int w, int h, int kind, uint32_t seed) {
  std::vector<uint8_t> y(static_cast<size_t>(w) * h);
  uint32_t state = seed;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      state = state * 1664525u + 1013904223u;
      uint8_t v;
      if (kind == 0)
        v = static_cast<uint8_t>(state >> 24);
      else if (kind == 1)
        v = static_cast<uint8_t>(128 + 100 * std::sin(0.05 * c + 0.03 * r) + ((c + r) % 3) * 9);
      else
        v = static_cast<uint8_t>(((state >> 24) & 3) == 0 ? 0 : ((state >> 24) & 3) == 1 ? 16
                                                        : ((state >> 24) & 3) == 2 ? 235 : 255);
      y[static_cast<size_t>(r) * w + c] = v;
    }
  return y;
}

// swscale's GRAY8 at half size from a frame of `format` with this luma (and
// random chroma, which must not matter).
std::vector<uint8_t> Swscale(const std::vector<uint8_t>& y, int w, int h, AVPixelFormat format) {
  std::vector<uint8_t> u(static_cast<size_t>(w) * h * 2, 77), v(static_cast<size_t>(w) * h, 201);
  const uint8_t* src[4] = {y.data(), u.data(), v.data(), nullptr};
  int stride[4] = {w, w, w, 0};
  if (format == AV_PIX_FMT_YUV420P || format == AV_PIX_FMT_YUV422P) stride[1] = stride[2] = w / 2;
  if (format == AV_PIX_FMT_NV12 || format == AV_PIX_FMT_NV21) stride[1] = w;  // interleaved
  SwsContext* sws = sws_getContext(w, h, format, w / 2, h / 2, AV_PIX_FMT_GRAY8, SWS_BILINEAR,
                                   nullptr, nullptr, nullptr);
  EXPECT_NE(sws, nullptr);
  std::vector<uint8_t> out(static_cast<size_t>(w / 2) * (h / 2) + 64);
  uint8_t* dst[4] = {out.data(), nullptr, nullptr, nullptr};
  const int dst_stride[4] = {w / 2, 0, 0, 0};
  sws_scale(sws, src, stride, 0, h, dst, dst_stride);
  sws_freeContext(sws);
  out.resize(static_cast<size_t>(w / 2) * (h / 2));
  return out;
}

bool OnX86_64() {
#if defined(__x86_64__) || defined(_M_X64)
  return true;
#else
  return false;
#endif
}

TEST(HalfGrayTest, SelfCheckAgreesOnX86) {
  // The replica is of swscale's x86 code: there it must agree, or the fast
  // path silently goes unused (ffmpeg_source.cc).
  if (!OnX86_64()) GTEST_SKIP() << "swscale's vertical rounding is x86-specific";
  EXPECT_TRUE(HalfGrayMatchesSwscale());
}

TEST(HalfGrayTest, SameBytesAsSwscaleForEveryLimitedRangeFormat) {
  if (!HalfGrayMatchesSwscale()) GTEST_SKIP() << "not this platform's swscale (checked above)";
  // Sizes: the smallest allowed, odd halves (w/2 not a multiple of 8: the
  // scalar tail), 1080p.
  const int sizes[][2] = {{8, 8}, {18, 10}, {62, 46}, {322, 182}, {1920, 1080}};
  const AVPixelFormat formats[] = {AV_PIX_FMT_YUV420P, AV_PIX_FMT_YUV422P, AV_PIX_FMT_YUV444P,
                                   AV_PIX_FMT_NV12, AV_PIX_FMT_NV21};
  for (const auto& size : sizes)
    for (AVPixelFormat format : formats)
      for (int kind = 0; kind < 3; ++kind) {
        const int w = size[0], h = size[1];
        const std::vector<uint8_t> y = Luma(w, h, kind, 7u + w * 31u + kind);
        const std::vector<uint8_t> theirs = Swscale(y, w, h, format);
        std::vector<uint8_t> ours(theirs.size(), 0xAA);
        HalfGrayFromLimitedLuma(y.data(), w, w, h, ours.data(), w / 2);
        size_t differ = 0;
        for (size_t i = 0; i < ours.size(); ++i) differ += ours[i] != theirs[i];
        EXPECT_EQ(differ, 0u) << w << "x" << h << " format " << format << " kind " << kind;
      }
}

TEST(HalfGrayTest, HonoursStridesAndRangeExpansion) {
  // A padded source and destination; flat limited-range black and white
  // come out as full-range 0 and 255, mid-grey as (128-16)*255/219.
  const int w = 40, h = 24, stride = 64, out_stride = 32;
  std::vector<uint8_t> y(static_cast<size_t>(stride) * h, 99);  // padding: 99
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) y[static_cast<size_t>(r) * stride + c] = c < w / 2 ? 16 : 235;
  std::vector<uint8_t> out(static_cast<size_t>(out_stride) * (h / 2), 7);
  HalfGrayFromLimitedLuma(y.data(), stride, w, h, out.data(), out_stride);
  for (int r = 0; r < h / 2; ++r) {
    EXPECT_EQ(out[static_cast<size_t>(r) * out_stride + 0], 0) << r;
    EXPECT_EQ(out[static_cast<size_t>(r) * out_stride + w / 2 - 1], 255) << r;
    EXPECT_EQ(out[static_cast<size_t>(r) * out_stride + w / 2], 7) << r;  // past the row: untouched
  }
  std::vector<uint8_t> mid(static_cast<size_t>(w) * h, 128), half(static_cast<size_t>(w / 2) * (h / 2));
  HalfGrayFromLimitedLuma(mid.data(), w, w, h, half.data(), w / 2);
  for (uint8_t v : half) EXPECT_NEAR(v, (128 - 16) * 255.0 / 219, 1.0);
}

}  // namespace
}  // namespace hapcine
