#pragma once
// The working gray image of a frame decoded at exactly twice the working
// size (1920x1080 -> 960x540), computed from the decoder's luma plane and
// byte for byte what libswscale 6.7 (FFmpeg 5.1) gives for limited-range
// 8-bit YUV -> GRAY8 with SWS_BILINEAR on x86-64: the same gray image, so the
// same tracks, at a fraction of the cost (swscale was ~8 % of the CPU of
// `hapcine estimate` on a 1080p clip; docs/extract.md "Speed").
//
// What swscale computes there, and this replica with it:
// - horizontal: the bilinear filter of a 2x shrink is [1 3 3 1] / 8 (14-bit
//   coefficients, edge taps folded onto the edge pixel), kept as 15-bit
//   intermediates (pixel << 7);
// - range: limited -> full ((min(v, 30189) * 19077 - 39057361) >> 14), as
//   GRAY8 is full range and YUV420P limited;
// - vertical: [1 3 3 1] / 8 in 12-bit coefficients (folded at the top and
//   bottom edges), summed with x86's pmulhw ((v * c) >> 16 per tap, 16-bit
//   sums, rounding constant 5, >> 3), except on the last two output rows,
//   where swscale switches to its exact C sum (((64 << 12) + sum v * c) >> 19).
// The pmulhw sum is FFmpeg's x86 code; elsewhere (or in another FFmpeg)
// swscale may round differently, so the caller asks HalfGrayMatchesSwscale()
// before using this (ffmpeg_source.cc). half_gray_test.cc checks
// it against sws_scale on random images of several sizes and formats.

#include <cstdint>

namespace hapcine {

// Whether this replica gives swscale's bytes here: both run once on a
// 64x48 test frame (random bytes, so clipping and the edges are covered);
// the answer is cached.
bool HalfGrayMatchesSwscale();

// `luma`: width x height 8-bit limited-range Y plane (`stride` bytes a row),
// width and height even and >= 8. `out`: (width/2) x (height/2), `out_stride`
// bytes a row.
void HalfGrayFromLimitedLuma(const uint8_t* luma, int stride, int width, int height, uint8_t* out,
                             int out_stride);

}  // namespace hapcine
