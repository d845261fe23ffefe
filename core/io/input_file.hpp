#pragma once

#include <cstdint>
#include <string>

namespace gr {

/// Checks, before anything opens it, that `path` names a regular file (a symlink to one
/// counts) of at most `max_bytes` bytes: devices, FIFOs and folders would block or never
/// end, and an oversized file would take the memory of the machine.
/// @throw InputError naming the path when it is missing, not a regular file, or too large.
void require_regular_file(const std::string& path, std::uintmax_t max_bytes = UINTMAX_MAX);

}  // namespace gr
