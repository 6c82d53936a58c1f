#include "rpsd/output/provenance.h"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "rpsd/build_info/build_info.h"

namespace rpsd::output {

std::string sha256_of_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read it to record its SHA-256");
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 is not available (OpenSSL)");
  }
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0) EVP_DigestUpdate(context.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error(file.string() + ": read failed while computing its SHA-256");
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  EVP_DigestFinal_ex(context.get(), digest.data(), &length);
  std::string hex;
  char pair[3];
  for (unsigned int i = 0; i < length; ++i) {
    std::snprintf(pair, sizeof pair, "%02x", digest[i]);
    hex += pair;
  }
  return hex;
}

nlohmann::json provenance_json(const std::vector<std::filesystem::path>& input_files) {
  nlohmann::json inputs = nlohmann::json::array();
  for (const auto& file : input_files) {
    inputs.push_back(
        {{"file", std::filesystem::absolute(file).lexically_normal().string()}, {"sha256", sha256_of_file(file)}});
  }
  return {{"rpsd", {{"version", build_info::version()}, {"commit", build_info::commit()}}}, {"inputs", inputs}};
}

}  // namespace rpsd::output
