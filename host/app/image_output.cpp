#include "image_output.hpp"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "png.hpp"

namespace clothsim {
namespace fs = std::filesystem;

void write_png(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba) {
  try {
    write_png_file(path, w, h, rgba);
  } catch (const std::runtime_error& e) {
    throw ExitError(kExitBadInput, e.what());
  }
}

// GIF frame delays are whole hundredths of a second, and browsers play delays under 2/100 s
// at 1/10 s instead: a faster GIF would play several times too slowly.
constexpr double kGifMaxFps = 50;

void FrameSink::check(const std::string& out, int w, int h, double fps) {
  const std::string ext = fs::path(out).extension().string();
  if (ext != ".mp4" && ext != ".gif") return;
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    throw ExitError(kExitBadInput, fmt::format("--out {}: making an {} needs ffmpeg, which is not installed "
                                               "(apt-get install ffmpeg), or write PNGs with --out DIR",
                                               out, ext == ".mp4" ? "MP4" : "animated GIF"));
  if (ext == ".mp4" && (w % 2 || h % 2))
    throw ExitError(kExitBadInput, fmt::format("--size {}x{}: an MP4 (yuv420p) needs an even width and height", w, h));
  if (ext == ".gif" && fps > kGifMaxFps)
    throw ExitError(kExitBadInput, fmt::format("--out {}: {:g} frames/s is faster than a GIF can play (at most {:g}); "
                                               "keep every 2nd frame with --every 2, or set --fps",
                                               out, fps, kGifMaxFps));
}

FrameSink::FrameSink(const std::string& out, int w, int h, double fps)
    : out_(out), width_(w), height_(h), fps_(fps) {
  check(out, w, h, fps);
  const std::string ext = fs::path(out).extension().string();
  if (ext == ".mp4" || ext == ".gif") {
    kind_ = ext == ".mp4" ? Kind::Video : Kind::Gif;
    start_ffmpeg(kind_ == Kind::Video
                     ? "-c:v libx264 -pix_fmt yuv420p -movflags +faststart"
                     // One palette for the whole clip, made from every frame (stats_mode=diff
                     // favours what moves), ordered dithering (error diffusion crawls from frame
                     // to frame) and only the changed rectangle stored per frame: small files.
                     : "-filter_complex \"split[a][b];[a]palettegen=stats_mode=diff[p];"
                       "[b][p]paletteuse=dither=bayer:bayer_scale=3:diff_mode=rectangle\" -loop 0");
  } else if (ext == ".png") {
    kind_ = Kind::Still;
  } else {
    kind_ = Kind::Directory;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out))
      throw ExitError(kExitBadInput, fmt::format("--out {}: cannot create the directory ({})", out, ec.message()));
  }
}

void FrameSink::start_ffmpeg(const std::string& encoder_args) {
  const std::string cmd = fmt::format("ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgba -s {}x{} -framerate {} -i - {} '{}'",
                                      width_, height_, fps_, encoder_args, out_);
  ffmpeg_ = popen(cmd.c_str(), "w");
  if (!ffmpeg_) throw ExitError(kExitBadInput, fmt::format("--out {}: cannot start ffmpeg", out_));
}

FrameSink::~FrameSink() {
  if (ffmpeg_) pclose(ffmpeg_);
}

void FrameSink::add(const std::vector<uint8_t>& rgba) {
  switch (kind_) {
    case Kind::Video:
    case Kind::Gif:
      if (std::fwrite(rgba.data(), 1, rgba.size(), ffmpeg_) != rgba.size())
        throw ExitError(kExitCheckFailed, fmt::format("{}: ffmpeg stopped accepting frames", out_));
      break;
    case Kind::Still: last_ = rgba; break;
    case Kind::Directory:
      write_png((fs::path(out_) / fmt::format("frame_{:04d}.png", frames_)).string(), width_, height_, rgba);
      break;
  }
  ++frames_;
}

std::string FrameSink::finish() {
  switch (kind_) {
    case Kind::Video:
    case Kind::Gif: {
      const int status = pclose(ffmpeg_);
      ffmpeg_ = nullptr;
      if (status != 0) throw ExitError(kExitCheckFailed, fmt::format("{}: ffmpeg failed (status {})", out_, status));
      return fmt::format("wrote {} ({} frames, {}, {:g} frames/s)", out_, frames_,
                         kind_ == Kind::Video ? "H.264" : "GIF", fps_);
    }
    case Kind::Still:
      if (!last_.empty()) write_png(out_, width_, height_, last_);
      return fmt::format("wrote {} (frame {})", out_, frames_);
    case Kind::Directory: break;
  }
  return fmt::format("wrote {} frames to {}/frame_0000.png ...", frames_, out_);
}

}  // namespace clothsim
