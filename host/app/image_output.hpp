// Where rendered frames go: PNG files (one per frame, or the last frame only), or an MP4 or
// an animated GIF made by piping raw frames into ffmpeg. Every file replaces the one it names
// only once complete (docs/export.md): written under a temporary name beside it, then renamed.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/output_file.hpp"

namespace clothsim {

// Written to a temporary beside `path` and renamed once complete; ExitError (2) if it cannot be.
void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

// The argument vector `render --out FILE.mp4|FILE.gif` starts ffmpeg with (no shell): raw RGBA
// frames of `width` x `height` on stdin at `fps`, encoded into `output`, which is passed as one
// element with ffmpeg's `file:` prefix, so no character of it (a leading '-', quotes, ';',
// '$(...)', ':') is read as anything but the file's name.
std::vector<std::string> ffmpeg_arguments(bool gif, int width, int height, double fps, const std::string& output);

class FrameSink {
 public:
  // `out`: DIR (frame_0000.png ...), FILE.png (last frame only), FILE.mp4 or FILE.gif, played
  // at `fps` frames per second. Throws ExitError (2) for an unusable destination, a missing
  // ffmpeg or a frame rate a GIF cannot play.
  FrameSink(const std::string& out, int width, int height, double fps);
  // The same checks, with nothing started or created: to refuse bad options before any work.
  static void check(const std::string& out, int width, int height, double fps);
  ~FrameSink();  // unfinished: stops ffmpeg and removes its temporary; `out` is left as it was
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;
  bool last_frame_only() const { return kind_ == Kind::Still; }
  void add(const std::vector<uint8_t>& rgba);
  // Flushes; an MP4 or GIF is renamed over `out` only if ffmpeg succeeded (ExitError 1
  // otherwise, with `out` left as it was). Returns a sentence saying what was written.
  std::string finish();

 private:
  enum class Kind { Directory, Still, Video, Gif } kind_;
  void start_ffmpeg();
  std::string stop_ffmpeg();  // closes its input, waits; "" when it exited 0, else how it ended
  std::string out_;
  int width_, height_;
  double fps_;
  int frames_ = 0;
  std::vector<uint8_t> last_;
  std::unique_ptr<PendingFile> video_;  // the temporary ffmpeg writes, renamed over out_ on success
  pid_t ffmpeg_ = -1;
  int ffmpeg_input_ = -1;  // the write end of the pipe to ffmpeg's stdin
};

}  // namespace clothsim
