#pragma once

#include <string>

namespace gr {

/// Creates `out_dir` (and its parents) when missing.
/// @throw OutputError when it cannot be created or is not a folder.
void prepare_output_folder(const std::string& out_dir);

}  // namespace gr
