#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace gr {

/// Writes a file through `write` into a temporary file beside `path`, then renames it
/// over `path`: readers see either the old file or the complete new one, never a part.
/// @throw OutputError when the folder is not writable or writing fails; the temporary
///        file is removed.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace gr
