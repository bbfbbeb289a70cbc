// Every file clothsim reads (scene, mesh, state, point cache, texture) is checked here before it
// is opened: a FIFO, a device (/dev/zero) or a directory would block a read or never end, and
// an empty path would otherwise mean "the current directory" or "the built-in scene".
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace clothsim {

// A failed stat/open's errno in words ("does not exist", "a loop of symbolic links (ELOOP: ...)",
// "the name is too long (ENAMETOOLONG)", ...): shared by the input and the output checks.
std::string errno_words(int e);
// What a file of mode `mode` is, for a message: "a directory", "a FIFO (named pipe)", "a
// character device", "a block device", "a socket", "a regular file" or "not a plain file".
std::string file_kind(unsigned mode);

// Why `path` cannot be read as an input file, in words ("is a FIFO (named pipe), not a regular
// file", "a loop of symbolic links (ELOOP)", ...), or nullopt when it is a regular file; then
// `size` (if given) gets its size in bytes. Only stat(2): nothing is opened, nothing blocks.
std::optional<std::string> input_file_problem(const std::filesystem::path& path, uint64_t* size = nullptr);

// The whole of a regular file of at most `max_bytes`, opened with O_NONBLOCK and checked again
// on the open descriptor (the name may have been replaced since the stat). Throws
// std::runtime_error with the problem in words (without the path: callers name the file).
std::string read_input_file(const std::filesystem::path& path, uint64_t max_bytes);

// `s` with every control character (C0, DEL) written as \xNN, so a name read from a file
// (a state's scene name, a scene's key or mesh path) cannot move the cursor or recolour the
// terminal when printed. Newlines too, unless keep_newlines (for our own multi-line messages).
std::string printable(std::string_view s, bool keep_newlines = false);

}  // namespace clothsim
