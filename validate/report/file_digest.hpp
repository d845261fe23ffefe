#pragma once

#include <string>

namespace gr {

/// SHA-256 of a file's bytes as 64 lowercase hex digits (OpenSSL libcrypto).
/// @throw InputError when the file cannot be read.
std::string sha256_of_file(const std::string& path);

/// SHA-256 of `text`'s bytes as 64 lowercase hex digits.
std::string sha256_of_text(const std::string& text);

}  // namespace gr
