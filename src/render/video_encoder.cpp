#include "render/video_encoder.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
}

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <system_error>
#include <thread>

#include "image/yuv420.hpp"
#include "sys/temporaries.hpp"

namespace stiction::render {
namespace {

std::string av_message(int code) {
  char buffer[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buffer, sizeof buffer);
  return buffer;
}

struct CodecContextDeleter {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameDeleter {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketDeleter {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
// Closes the file (if open) and frees the muxer.
struct FormatDeleter {
  void operator()(AVFormatContext* f) const {
    if (f->pb && !(f->oformat->flags & AVFMT_NOFILE)) avio_closep(&f->pb);
    avformat_free_context(f);
  }
};

}  // namespace

int encoder_threads() {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  int renderer = cores;
  if (const char* lp = std::getenv("LP_NUM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(lp, &end, 10);
    // 0: llvmpipe rasterizes on the calling thread.
    if (end != lp && n >= 0) renderer = static_cast<int>(std::clamp<long>(n, 1, cores));
  }
  return std::max(1, cores - renderer);
}

struct VideoEncoder::State {
  std::unique_ptr<AVFormatContext, FormatDeleter> format;
  std::unique_ptr<AVCodecContext, CodecContextDeleter> codec;
  std::unique_ptr<AVFrame, FrameDeleter> frame;
  std::unique_ptr<AVPacket, PacketDeleter> packet;
  AVStream* stream = nullptr;  // owned by format
  long frames = 0;
  bool finished = false;
};

VideoEncoder::VideoEncoder(std::filesystem::path path, const VideoOptions& options)
    : path_(std::move(path)), state_(std::make_unique<State>()) {
  if (options.width <= 0 || options.height <= 0 || options.width % 2 || options.height % 2) {
    throw VideoError("video size must be even and positive, got " + std::to_string(options.width) +
                     "x" + std::to_string(options.height));
  }
  // The temporary is created here, exclusively (sys/temporaries.hpp), and handed to libav as
  // a "file:" URL of its absolute path: an output directory named "run:1" or "tcp://..."
  // must stay a file name, never select another protocol.
  try {
    const sys::Temporary created = sys::create_temporary(path_);
    ::close(created.fd);
    temp_ = created.path;
  } catch (const std::system_error& e) {
    throw VideoError("cannot write " + path_.string() + ": " + e.code().message());
  }
  std::error_code absolute_error;
  const std::string url = "file:" + std::filesystem::absolute(temp_, absolute_error).string();

  try {
    open(url, options);
  } catch (...) {
    state_.reset();  // closes the file, if libav opened it
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    sys::forget_temporary(temp_);
    throw;
  }
}

void VideoEncoder::open(const std::string& url, const VideoOptions& options) {
  State& s = *state_;
  // libx264 prints statistics at info level on stderr, which would garble the progress bar.
  // (The level is process-wide in FFmpeg; only errors are wanted from it anywhere here.)
  if (av_log_get_level() > AV_LOG_ERROR) av_log_set_level(AV_LOG_ERROR);
  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec)
    throw VideoError("libavcodec has no libx264 encoder (Debian: libavcodec-extra59 or libx264)");

  AVFormatContext* format = nullptr;
  int rc = avformat_alloc_output_context2(&format, nullptr, "mp4", url.c_str());
  if (rc < 0 || !format) throw VideoError("cannot create an MP4 muxer: " + av_message(rc));
  s.format.reset(format);

  s.codec.reset(avcodec_alloc_context3(codec));
  if (!s.codec) throw VideoError("out of memory (codec context)");
  AVCodecContext* c = s.codec.get();
  const AVRational rate = av_d2q(options.fps, 100000);
  c->width = options.width;
  c->height = options.height;
  c->framerate = rate;
  c->time_base = av_inv_q(rate);
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->gop_size = static_cast<int>(options.fps * 2.0);
  c->color_primaries = AVCOL_PRI_BT709;
  c->color_trc = AVCOL_TRC_BT709;
  c->colorspace = AVCOL_SPC_BT709;
  c->color_range = AVCOL_RANGE_MPEG;
  c->chroma_sample_location = AVCHROMA_LOC_LEFT;  // as image::rgba_to_yuv420_bt709 sites it
  if (s.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(c->priv_data, "preset", options.preset.c_str(), 0);
  av_opt_set(c->priv_data, "crf", std::to_string(options.crf).c_str(), 0);
  // ultrafast turns the in-loop deblocking filter off, which leaves block edges on the smooth
  // surfaces we render (SSIM 0.989 against 0.992 with it). Back on at strength 1:1 (x264's
  // tune "animation", whose pictures are like ours), it costs about half a millisecond per
  // 720p frame, and gives a smaller file than 0:0 at better SSIM.
  if (options.preset == "ultrafast") av_opt_set(c->priv_data, "deblock", "1:1", 0);
  // -1: libavcodec/x264 choose (1.5 threads per core: oversubscribed beside the renderer).
  c->thread_count =
      options.threads > 0 ? options.threads : (options.threads < 0 ? 0 : encoder_threads());
  rc = avcodec_open2(c, codec, nullptr);
  if (rc < 0) throw VideoError("cannot open the H.264 encoder: " + av_message(rc));

  s.stream = avformat_new_stream(s.format.get(), nullptr);
  if (!s.stream) throw VideoError("out of memory (stream)");
  s.stream->time_base = c->time_base;
  s.stream->avg_frame_rate = rate;
  rc = avcodec_parameters_from_context(s.stream->codecpar, c);
  if (rc < 0) throw VideoError("cannot set stream parameters: " + av_message(rc));

  rc = avio_open(&s.format->pb, url.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) throw VideoError("cannot write " + path_.string() + ": " + av_message(rc));
  // faststart: the muxer rewrites the file at the end with `moov` moved before `mdat`.
  AVDictionary* muxer_options = nullptr;
  av_dict_set(&muxer_options, "movflags", "+faststart", 0);
  rc = avformat_write_header(s.format.get(), &muxer_options);
  av_dict_free(&muxer_options);
  if (rc < 0) {
    s.format.reset();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    throw VideoError("cannot write the MP4 header of " + path_.string() + ": " + av_message(rc));
  }

  s.frame.reset(av_frame_alloc());
  s.packet.reset(av_packet_alloc());
  if (!s.frame || !s.packet) throw VideoError("out of memory (frame)");
  s.frame->format = AV_PIX_FMT_YUV420P;
  s.frame->width = options.width;
  s.frame->height = options.height;
  s.frame->color_primaries = AVCOL_PRI_BT709;
  s.frame->color_trc = AVCOL_TRC_BT709;
  s.frame->colorspace = AVCOL_SPC_BT709;
  s.frame->color_range = AVCOL_RANGE_MPEG;
  s.frame->chroma_location = AVCHROMA_LOC_LEFT;
  rc = av_frame_get_buffer(s.frame.get(), 0);
  if (rc < 0) throw VideoError("cannot allocate a frame: " + av_message(rc));
}

VideoEncoder::~VideoEncoder() {
  if (state_ && !state_->finished) {
    state_.reset();  // closes the file
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
  if (!temp_.empty()) sys::forget_temporary(temp_);
}

long VideoEncoder::frames_written() const { return state_->frames; }

void VideoEncoder::drain(bool flush) {
  State& s = *state_;
  for (;;) {
    const int rc = avcodec_receive_packet(s.codec.get(), s.packet.get());
    if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
    if (rc < 0) throw VideoError("H.264 encoding failed: " + av_message(rc));
    av_packet_rescale_ts(s.packet.get(), s.codec->time_base, s.stream->time_base);
    s.packet->stream_index = s.stream->index;
    const int wrc = av_interleaved_write_frame(s.format.get(), s.packet.get());
    if (wrc < 0) throw VideoError("cannot write " + path_.string() + ": " + av_message(wrc));
  }
  (void)flush;
}

void VideoEncoder::encode(const image::Image& image) {
  State& s = *state_;
  if (s.finished) throw VideoError("encode() after finish()");
  if (image.width != s.codec->width || image.height != s.codec->height) {
    throw VideoError("frame size " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " differs from the video's");
  }
  int rc = av_frame_make_writable(s.frame.get());
  if (rc < 0) throw VideoError("cannot reuse the frame: " + av_message(rc));
  AVFrame& f = *s.frame;
  image::rgba_to_yuv420_bt709(
      image, {f.data[0], f.linesize[0], f.data[1], f.linesize[1], f.data[2], f.linesize[2]});
  s.frame->pts = s.frames++;
  rc = avcodec_send_frame(s.codec.get(), s.frame.get());
  if (rc < 0) throw VideoError("H.264 encoding failed: " + av_message(rc));
  drain(false);
}

std::filesystem::path VideoEncoder::finish(const std::filesystem::path& final_path) {
  State& s = *state_;
  if (s.finished) throw VideoError("finish() called twice");
  int rc = avcodec_send_frame(s.codec.get(), nullptr);
  if (rc < 0) throw VideoError("cannot flush the encoder: " + av_message(rc));
  drain(true);
  rc = av_write_trailer(s.format.get());
  if (rc < 0) throw VideoError("cannot finish " + path_.string() + ": " + av_message(rc));
  rc = avio_closep(&s.format->pb);
  if (rc < 0) throw VideoError("cannot close " + path_.string() + ": " + av_message(rc));
  const std::filesystem::path target = final_path.empty() ? path_ : final_path;
  std::error_code ec;
  std::filesystem::rename(temp_, target, ec);
  if (!ec) sys::forget_temporary(temp_);
  if (ec) throw VideoError("cannot rename " + temp_.string() + " to " + target.string() + ": " + ec.message());
  s.finished = true;
  return target;
}

}  // namespace stiction::render
