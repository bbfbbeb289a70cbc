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

FrameSink::FrameSink(const std::string& out, int w, int h, double fps) : out_(out), width_(w), height_(h) {
  const std::string ext = fs::path(out).extension().string();
  if (ext == ".mp4") {
    kind_ = Kind::Video;
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
      throw ExitError(kExitBadInput, fmt::format("--out {}: making an MP4 needs ffmpeg, which is not installed "
                                                 "(apt-get install ffmpeg), or write PNGs with --out DIR",
                                                 out));
    if (w % 2 || h % 2)
      throw ExitError(kExitBadInput, fmt::format("--size {}x{}: an MP4 (yuv420p) needs an even width and height", w, h));
    const std::string cmd = fmt::format(
        "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgba -s {}x{} -framerate {} -i - "
        "-c:v libx264 -pix_fmt yuv420p -movflags +faststart '{}'",
        w, h, fps, out);
    ffmpeg_ = popen(cmd.c_str(), "w");
    if (!ffmpeg_) throw ExitError(kExitBadInput, fmt::format("--out {}: cannot start ffmpeg", out));
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

FrameSink::~FrameSink() {
  if (ffmpeg_) pclose(ffmpeg_);
}

void FrameSink::add(const std::vector<uint8_t>& rgba) {
  switch (kind_) {
    case Kind::Video:
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
    case Kind::Video: {
      const int status = pclose(ffmpeg_);
      ffmpeg_ = nullptr;
      if (status != 0) throw ExitError(kExitCheckFailed, fmt::format("{}: ffmpeg failed (status {})", out_, status));
      return fmt::format("wrote {} ({} frames, H.264)", out_, frames_);
    }
    case Kind::Still:
      if (!last_.empty()) write_png(out_, width_, height_, last_);
      return fmt::format("wrote {} (frame {})", out_, frames_);
    case Kind::Directory: break;
  }
  return fmt::format("wrote {} frames to {}/frame_0000.png ...", frames_, out_);
}

}  // namespace clothsim
