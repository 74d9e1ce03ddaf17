#include "render/video_encoder.hpp"

#include <cstdio>
#include <optional>

#include <fmt/format.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "render/offscreen_context.hpp"

namespace gpm::render {
namespace {

std::string av_error(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, buf, sizeof(buf));
  return buf;
}

}  // namespace

struct VideoEncoder::Impl {
  std::string path, tmp;  // tmp: where libav writes (the staged file, or a device in place)
  std::optional<gpm::OutputFile> out;  // discarded unless finished
  int width = 0, height = 0;
  AVFormatContext* fmt = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  bool file_open = false;
  bool finished = false;

  ~Impl() {
    if (sws) sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (fmt) {
      if (file_open) avio_closep(&fmt->pb);
      avformat_free_context(fmt);
    }
  }

  // Sends frame f (nullptr: flush) and writes every packet the encoder returns.
  void encode(const AVFrame* f) {
    int rc = avcodec_send_frame(codec, f);
    if (rc < 0) throw RenderError(fmt::format("video encoder: {}", av_error(rc)));
    for (;;) {
      rc = avcodec_receive_packet(codec, packet);
      if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
      if (rc < 0) throw RenderError(fmt::format("video encoder: {}", av_error(rc)));
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_interleaved_write_frame(fmt, packet);
      if (rc < 0) throw InputError(fmt::format("{}: cannot write: {}", path, av_error(rc)));
    }
  }
};

VideoEncoder::VideoEncoder(const std::string& path, int width, int height, double fps,
                           const VideoSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  av_log_set_level(AV_LOG_ERROR);
  Impl& im = *impl_;
  im.path = path;
  im.width = width;
  im.height = height;
  if (width <= 0 || height <= 0 || width % 2 || height % 2)
    throw InputError(fmt::format("{}: video size {}x{} must be positive and even", path, width, height));
  if (!(fps > 0)) throw InputError(fmt::format("{}: frame rate must be positive, got {}", path, fps));
  im.out.emplace(path);  // models/output_file.hpp: staged, or in place for a device
  im.tmp = im.out->write_path();

  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_H264);
  if (!codec) throw RenderError("no H.264 encoder in libavcodec (install libavcodec with libx264)");
  int rc = avformat_alloc_output_context2(&im.fmt, nullptr, "mp4", im.tmp.c_str());
  if (rc < 0 || !im.fmt) throw RenderError(fmt::format("libavformat: no MP4 muxer: {}", av_error(rc)));
  im.stream = avformat_new_stream(im.fmt, nullptr);
  im.codec = avcodec_alloc_context3(codec);
  im.frame = av_frame_alloc();
  im.packet = av_packet_alloc();
  if (!im.stream || !im.codec || !im.frame || !im.packet) throw RenderError("libav: out of memory");

  const AVRational rate = av_d2q(fps, 100000);
  im.codec->width = width;
  im.codec->height = height;
  im.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  im.codec->time_base = av_inv_q(rate);
  im.codec->framerate = rate;
  im.codec->colorspace = AVCOL_SPC_SMPTE170M;  // swscale's default RGB -> YUV matrix (BT.601)
  im.codec->color_range = AVCOL_RANGE_MPEG;
  if (im.fmt->oformat->flags & AVFMT_GLOBALHEADER) im.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(im.codec->priv_data, "preset", settings.preset.c_str(), 0);
  av_opt_set(im.codec->priv_data, "crf", std::to_string(settings.crf).c_str(), 0);
  rc = avcodec_open2(im.codec, codec, nullptr);
  if (rc < 0) throw RenderError(fmt::format("cannot open the H.264 encoder: {}", av_error(rc)));
  rc = avcodec_parameters_from_context(im.stream->codecpar, im.codec);
  if (rc < 0) throw RenderError(fmt::format("libav: {}", av_error(rc)));
  im.stream->time_base = im.codec->time_base;
  im.stream->avg_frame_rate = rate;

  rc = avio_open(&im.fmt->pb, im.tmp.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) throw InputError(fmt::format("{}: cannot write: {}", path, av_error(rc)));
  im.file_open = true;
  rc = avformat_write_header(im.fmt, nullptr);
  if (rc < 0) throw InputError(fmt::format("{}: cannot write: {}", path, av_error(rc)));

  im.frame->format = AV_PIX_FMT_YUV420P;
  im.frame->width = width;
  im.frame->height = height;
  rc = av_frame_get_buffer(im.frame, 0);
  if (rc < 0) throw RenderError(fmt::format("libav: {}", av_error(rc)));
  im.sws = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P, SWS_BILINEAR,
                          nullptr, nullptr, nullptr);
  if (!im.sws) throw RenderError("libswscale: cannot convert RGB to YUV 4:2:0");
}

VideoEncoder::~VideoEncoder() = default;

void VideoEncoder::add_frame(const FrameImage& img) {
  Impl& im = *impl_;
  if (im.finished) throw RenderError("video encoder: frame after finish()");
  if (img.width != im.width || img.height != im.height)
    throw RenderError(fmt::format("video encoder: frame is {}x{}, video is {}x{}", img.width, img.height,
                                  im.width, im.height));
  int rc = av_frame_make_writable(im.frame);
  if (rc < 0) throw RenderError(fmt::format("libav: {}", av_error(rc)));
  const uint8_t* src[1] = {img.rgb.data()};
  const int src_stride[1] = {img.width * 3};
  sws_scale(im.sws, src, src_stride, 0, img.height, im.frame->data, im.frame->linesize);
  im.frame->pts = frames_;
  im.encode(im.frame);
  ++frames_;
}

void VideoEncoder::finish() {
  Impl& im = *impl_;
  if (im.finished) return;
  im.encode(nullptr);
  int rc = av_write_trailer(im.fmt);
  if (rc < 0) throw InputError(fmt::format("{}: cannot write: {}", im.path, av_error(rc)));
  rc = avio_closep(&im.fmt->pb);
  im.file_open = false;
  if (rc < 0) throw InputError(fmt::format("{}: cannot write: {}", im.path, av_error(rc)));
  im.out->commit();
  im.finished = true;
}

std::string VideoEncoder::codec_name() const { return impl_->codec && impl_->codec->codec ? impl_->codec->codec->name : ""; }

}  // namespace gpm::render
