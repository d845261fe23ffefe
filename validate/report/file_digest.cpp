#include "validate/report/file_digest.hpp"

#include <array>
#include <fstream>
#include <memory>

#include <openssl/evp.h>

#include "core/common/errors.hpp"

namespace gr {

namespace {

using DigestContext = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

DigestContext start_sha256() {
  DigestContext context(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL SHA-256 initialisation failed");
  return context;
}

std::string finish_sha256(EVP_MD_CTX* context) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  EVP_DigestFinal_ex(context, digest.data(), &length);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

}  // namespace

std::string sha256_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file to hash");
  const DigestContext context = start_sha256();
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    const auto count = in.gcount();
    if (count > 0) EVP_DigestUpdate(context.get(), buffer.data(), static_cast<std::size_t>(count));
  }
  if (in.bad()) throw InputError(path, 0, "read error while hashing");
  return finish_sha256(context.get());
}

std::string sha256_of_text(const std::string& text) {
  const DigestContext context = start_sha256();
  EVP_DigestUpdate(context.get(), text.data(), text.size());
  return finish_sha256(context.get());
}

}  // namespace gr
