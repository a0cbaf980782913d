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
Status write_file_whole(const std::string& path, std::span<const std::uint8_t> bytes);
Status write_file_whole(const std::string& path, std::string_view text);

}  // namespace carbtf
