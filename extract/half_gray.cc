#include "extract/half_gray.h"

#include <algorithm>
#include <vector>

extern "C" {
#include <libswscale/swscale.h>
}

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace hapcine {
namespace {

// swscale's 15-bit intermediate of a 2x bilinear shrink, range-expanded:
// t = sum of the [1 3 3 1] taps (0..2040); (t * 2048) >> 7 = t << 4 exactly.
inline int16_t RangeExpanded(int t) {
  const int v = std::min(t << 4, 30189);
  return static_cast<int16_t>((v * 19077 - 39057361) >> 14);
}

// One input row -> `w` range-expanded 15-bit samples.
void HorizontalRow(const uint8_t* s, int width, int16_t* out) {
  const int w = width / 2;
  auto scalar = [&](int x) {
    const int p = s[std::max(2 * x - 1, 0)], n = s[std::min(2 * x + 2, width - 1)];
    out[x] = RangeExpanded(p + n + 3 * (s[2 * x] + s[2 * x + 1]));
  };
  int x = 0;
  scalar(x++);
#if defined(__SSE2__)
  // 8 outputs read s[2x-2 .. 2x+17]: bytes as 16-bit words, low byte = even pixel.
  const __m128i low = _mm_set1_epi16(0xff), cap = _mm_set1_epi16(30189),
                gain = _mm_set1_epi16(19077), offset = _mm_set1_epi32(39057361);
  for (; x + 8 <= w - 1; x += 8) {
    const uint8_t* q = s + 2 * x;
    const __m128i pairs = _mm_loadu_si128(reinterpret_cast<const __m128i*>(q));
    const __m128i before = _mm_loadu_si128(reinterpret_cast<const __m128i*>(q - 2));
    const __m128i after = _mm_loadu_si128(reinterpret_cast<const __m128i*>(q + 2));
    const __m128i even = _mm_and_si128(pairs, low), odd = _mm_srli_epi16(pairs, 8);
    const __m128i p = _mm_srli_epi16(before, 8), n = _mm_and_si128(after, low);
    const __m128i eo = _mm_add_epi16(even, odd);
    const __m128i t = _mm_add_epi16(_mm_add_epi16(p, n), _mm_add_epi16(eo, _mm_add_epi16(eo, eo)));
    const __m128i v = _mm_min_epi16(_mm_slli_epi16(t, 4), cap);
    const __m128i lo = _mm_mullo_epi16(v, gain), hi = _mm_mulhi_epi16(v, gain);
    const __m128i a = _mm_srai_epi32(_mm_sub_epi32(_mm_unpacklo_epi16(lo, hi), offset), 14);
    const __m128i b = _mm_srai_epi32(_mm_sub_epi32(_mm_unpackhi_epi16(lo, hi), offset), 14);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), _mm_packs_epi32(a, b));
  }
#endif
  for (; x < w; ++x) scalar(x);
}

// x86 swscale's vertical sum: per tap (v * c) >> 16 (pmulhw), 16-bit sums
// starting at 5, >> 3, saturated to 0..255.
void VerticalMmx(const int16_t* const* rows, const int16_t* coef, int taps, int w, uint8_t* out) {
  int x = 0;
#if defined(__SSE2__)
  if (taps == 4) {  // every row but the first (3 taps there)
    const __m128i c0 = _mm_set1_epi16(coef[0]), c1 = _mm_set1_epi16(coef[1]),
                  c2 = _mm_set1_epi16(coef[2]), c3 = _mm_set1_epi16(coef[3]), five = _mm_set1_epi16(5);
    auto tap = [&](int k, __m128i c) {
      return _mm_mulhi_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(rows[k] + x)), c);
    };
    for (; x + 8 <= w; x += 8) {
      const __m128i sum = _mm_add_epi16(_mm_add_epi16(tap(0, c0), tap(1, c1)),
                                        _mm_add_epi16(_mm_add_epi16(tap(2, c2), tap(3, c3)), five));
      const __m128i v = _mm_srai_epi16(sum, 3);
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out + x), _mm_packus_epi16(v, v));
    }
  }
#endif
  for (; x < w; ++x) {
    int16_t acc = 5;
    for (int k = 0; k < taps; ++k) acc = static_cast<int16_t>(acc + ((rows[k][x] * coef[k]) >> 16));
    out[x] = static_cast<uint8_t>(std::clamp(acc >> 3, 0, 255));
  }
}

// swscale's exact C sum, used for its last two output rows.
void VerticalExact(const int16_t* const* rows, const int16_t* coef, int taps, int w, uint8_t* out) {
  for (int x = 0; x < w; ++x) {
    int v = 64 << 12;
    for (int k = 0; k < taps; ++k) v += rows[k][x] * coef[k];
    out[x] = static_cast<uint8_t>(std::clamp(v >> 19, 0, 255));
  }
}

}  // namespace

void HalfGrayFromLimitedLuma(const uint8_t* luma, int stride, int width, int height, uint8_t* out,
                             int out_stride) {
  const int w = width / 2, h = height / 2;
  // Input row r lives in slot r % 4: output row y reads rows 2y-1 .. 2y+2.
  std::vector<int16_t> ring(4 * static_cast<size_t>(w));
  auto slot = [&](int r) { return ring.data() + static_cast<size_t>(r & 3) * w; };
  int computed = 0;  // input rows [0, computed) done
  for (int y = 0; y < h; ++y) {
    const int last = std::min(2 * y + 2, height - 1);
    for (; computed <= last; ++computed)
      HorizontalRow(luma + static_cast<size_t>(computed) * stride, width, slot(computed));
    // [1 3 3 1] / 8 in 12 bits; a tap past an edge adds its weight to the
    // edge row (one product there, as in swscale's folded filter).
    const int16_t* rows[4];
    int16_t coef[4];
    int taps = 0;
    const int first = std::max(2 * y - 1, 0);
    for (int r = first; r <= last; ++r) {
      int c = (r == 2 * y || r == 2 * y + 1) ? 1536 : 512;
      if (r == 0 && 2 * y - 1 < 0) c += 512;
      if (r == height - 1 && 2 * y + 2 > height - 1) c += 512;
      rows[taps] = slot(r);
      coef[taps++] = static_cast<int16_t>(c);
    }
    uint8_t* dst = out + static_cast<size_t>(y) * out_stride;
    if (y >= h - 2)
      VerticalExact(rows, coef, taps, w, dst);
    else
      VerticalMmx(rows, coef, taps, w, dst);
  }
}

bool HalfGrayMatchesSwscale() {
  static const bool matches = [] {
    constexpr int kW = 64, kH = 48;
    std::vector<uint8_t> y(kW * kH), chroma(kW * kH / 4, 128), ours(kW * kH / 4),
        theirs(kW * kH / 4 + 64);
    uint32_t state = 12345;
    for (uint8_t& v : y) v = static_cast<uint8_t>((state = state * 1664525u + 1013904223u) >> 24);
    SwsContext* sws = sws_getContext(kW, kH, AV_PIX_FMT_YUV420P, kW / 2, kH / 2, AV_PIX_FMT_GRAY8,
                                     SWS_BILINEAR, nullptr, nullptr, nullptr);
    if (!sws) return false;
    const uint8_t* src[4] = {y.data(), chroma.data(), chroma.data(), nullptr};
    const int src_stride[4] = {kW, kW / 2, kW / 2, 0};
    uint8_t* dst[4] = {theirs.data(), nullptr, nullptr, nullptr};
    const int dst_stride[4] = {kW / 2, 0, 0, 0};
    sws_scale(sws, src, src_stride, 0, kH, dst, dst_stride);
    sws_freeContext(sws);
    HalfGrayFromLimitedLuma(y.data(), kW, kW, kH, ours.data(), kW / 2);
    return std::equal(ours.begin(), ours.end(), theirs.begin());
  }();
  return matches;
}

}  // namespace hapcine
