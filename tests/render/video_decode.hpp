// Decodes every frame of an MP4 to RGBA with libavformat/libavcodec/libswscale: the tests
// check the video against the PNG frames with it, and bench_render measures the video's
// quality (PSNR against the rendered frames) with it. Throws std::runtime_error.
#pragma once

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace stiction::render::testing {

struct DecodedVideo {
  std::string codec;
  int width = 0, height = 0;
  int frames = 0;
  double duration = 0.0;  // seconds, from the container
  double fps = 0.0;
  std::vector<image::Image> images;  // RGBA
};

inline DecodedVideo decode_video(const std::filesystem::path& path) {
  auto fail = [&](const std::string& what) {
    throw std::runtime_error("decoding " + path.string() + ": " + what);
  };
  DecodedVideo out;
  AVFormatContext* format_raw = nullptr;
  if (avformat_open_input(&format_raw, path.c_str(), nullptr, nullptr) != 0) fail("cannot open");
  std::unique_ptr<AVFormatContext, void (*)(AVFormatContext*)> format(
      format_raw, [](AVFormatContext* f) { avformat_close_input(&f); });
  if (avformat_find_stream_info(format.get(), nullptr) < 0) fail("no stream info");
  const int index = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (index < 0) fail("no video stream");
  AVStream* stream = format->streams[index];
  const AVCodec* codec = avcodec_find_decoder(stream->codecpar->codec_id);
  if (!codec) fail("no decoder");
  out.codec = codec->name;
  std::unique_ptr<AVCodecContext, void (*)(AVCodecContext*)> context(
      avcodec_alloc_context3(codec), [](AVCodecContext* c) { avcodec_free_context(&c); });
  avcodec_parameters_to_context(context.get(), stream->codecpar);
  if (avcodec_open2(context.get(), codec, nullptr) != 0) fail("cannot open the decoder");
  out.width = context->width;
  out.height = context->height;
  out.fps = av_q2d(stream->avg_frame_rate);
  out.duration = format->duration / double(AV_TIME_BASE);
  std::unique_ptr<AVPacket, void (*)(AVPacket*)> packet(av_packet_alloc(),
                                                        [](AVPacket* p) { av_packet_free(&p); });
  std::unique_ptr<AVFrame, void (*)(AVFrame*)> frame(av_frame_alloc(),
                                                     [](AVFrame* f) { av_frame_free(&f); });
  std::unique_ptr<SwsContext, void (*)(SwsContext*)> sws(nullptr, sws_freeContext);
  auto receive = [&] {
    while (avcodec_receive_frame(context.get(), frame.get()) == 0) {
      if (!sws) {
        sws.reset(sws_getContext(frame->width, frame->height,
                                 static_cast<AVPixelFormat>(frame->format), frame->width,
                                 frame->height, AV_PIX_FMT_RGBA, SWS_BILINEAR, nullptr, nullptr,
                                 nullptr));
        const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(sws.get(), bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16);
      }
      image::Image img(frame->width, frame->height);
      std::uint8_t* dst[1] = {img.pixels.data()};
      const int stride[1] = {static_cast<int>(img.stride())};
      sws_scale(sws.get(), frame->data, frame->linesize, 0, frame->height, dst, stride);
      out.images.push_back(std::move(img));
      ++out.frames;
    }
  };
  while (av_read_frame(format.get(), packet.get()) >= 0) {
    if (packet->stream_index == index) {
      avcodec_send_packet(context.get(), packet.get());
      receive();
    }
    av_packet_unref(packet.get());
  }
  avcodec_send_packet(context.get(), nullptr);
  receive();
  return out;
}

// PSNR in dB of `b` against `a` over R, G and B (alpha ignored); 99 for identical images.
inline double psnr_rgb(const image::Image& a, const image::Image& b) {
  double sum = 0.0;
  long n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(a.pixels[i]) - double(b.pixels[i]);
    sum += d * d;
    ++n;
  }
  if (sum == 0.0) return 99.0;
  return 10.0 * std::log10(255.0 * 255.0 / (sum / double(n)));
}

}  // namespace stiction::render::testing
