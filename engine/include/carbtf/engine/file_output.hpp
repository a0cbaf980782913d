// Files that carbtf writes: whole or not at all, and never in place of something that is not a regular
// file. A command run as root with `--out /dev/full` must not replace the device with a regular file,
// and a full disk must be an error, not a truncated material reported as written.
//
// Thread safety: calls for different paths may run concurrently; for the same path they must not.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "carbtf/engine/status.hpp"

namespace carbtf {

// Success when `path` names nothing yet, or a regular file (directly or through a symbolic link);
// otherwise a file_error naming the path and what is there (a folder, a device, a FIFO, a socket, a
// link to nothing). The check a command makes before any work.
Status check_output_file(const std::string& path);

// Writes `bytes` to `path`, replacing a regular file there (keeping its permission bits) and writing
// through a symbolic link to one. The bytes go to a new temporary file beside the target, are flushed
// to the disk, and only then renamed over it: a failed write (ENOSPC, EIO, EFBIG, a short write, a
// failed fsync or close) returns a file_error naming the path and the system's reason, and leaves the
// target as it was and no temporary behind. Refuses, as check_output_file(), what is not a regular file.
//
// `flush` later skips the per-file fsync for a writer of thousands of files (a rendered BTF's 6,561
// images took 5 s instead of 1 s with it), which then calls flush_file_system() once when done: write
// and close errors are still reported per file, and what the disk reports on write-back, once.
enum class Flush { each_file, later };
Status write_file_whole(const std::string& path, std::span<const std::uint8_t> bytes,
                        Flush flush = Flush::each_file);
Status write_file_whole(const std::string& path, std::string_view text, Flush flush = Flush::each_file);

// Flushes the file system holding `path` (syncfs), reporting a write-back error of any file written
// there since as a file_error naming `path`.
Status flush_file_system(const std::string& path);

}  // namespace carbtf
