// Where rendered frames go: PNG files (one per frame, or the last frame only), or an MP4 or
// an animated GIF made by piping raw frames into ffmpeg.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace clothsim {

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

class FrameSink {
 public:
  // `out`: DIR (frame_0000.png ...), FILE.png (last frame only), FILE.mp4 or FILE.gif, played
  // at `fps` frames per second. Throws ExitError (2) for an unusable destination, a missing
  // ffmpeg or a frame rate a GIF cannot play.
  FrameSink(const std::string& out, int width, int height, double fps);
  // The same checks, with nothing started or created: to refuse bad options before any work.
  static void check(const std::string& out, int width, int height, double fps);
  ~FrameSink();
  bool last_frame_only() const { return kind_ == Kind::Still; }
  void add(const std::vector<uint8_t>& rgba);
  std::string finish();  // flushes; returns a sentence saying what was written

 private:
  enum class Kind { Directory, Still, Video, Gif } kind_;
  void start_ffmpeg(const std::string& encoder_args);
  std::string out_;
  int width_, height_;
  double fps_;
  int frames_ = 0;
  std::vector<uint8_t> last_;
  std::FILE* ffmpeg_ = nullptr;
};

}  // namespace clothsim
