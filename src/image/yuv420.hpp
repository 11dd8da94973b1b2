// RGBA to Y'CbCr 4:2:0 (BT.709, limited range): what the H.264 encoder takes. Written here
// rather than through libswscale because it runs on every video frame, on a machine whose
// cores the CPU renderer keeps busy, where every millisecond of it adds to the video's
// time: it costs under half of swscale's RGBA -> yuv420p path (bench_render BM_Yuv420_*:
// 1.0 against 2.3 ms per 1280x720 frame).
#pragma once

#include <cstdint>

#include "image/image.hpp"

namespace stiction::image {

// Where the three planes go (libav's AVFrame data/linesize). Chroma planes are half the
// width and half the height.
struct Yuv420Planes {
  std::uint8_t* y = nullptr;
  int y_stride = 0;
  std::uint8_t* u = nullptr;  // Cb
  int u_stride = 0;
  std::uint8_t* v = nullptr;  // Cr
  int v_stride = 0;
};

// Converts `rgba` (even width and height; alpha ignored; values taken as the gamma-encoded
// R'G'B' they are) to BT.709 limited range: Y' in [16, 235], Cb and Cr in [16, 240]. Each
// chroma sample is sited as H.264 assumes by default (chroma_sample_loc_type 0, "left"): on
// the even luma column, between the two luma rows. It is the [1 2 1] / 4 average of that
// column and its neighbours over both rows (the left edge repeats its column). Results are
// the exact values rounded to nearest, off by at most one code from fixed-point rounding.
// Throws ImageError for odd sizes.
void rgba_to_yuv420_bt709(const Image& rgba, const Yuv420Planes& out);

}  // namespace stiction::image
