// SHA-256 (FIPS 180-4) of files and strings, for the provenance recorded in model files.
#pragma once

#include <string>
#include <string_view>

namespace stiffpath::core {

//! Lower-case hex SHA-256 of a byte string.
std::string sha256_hex(std::string_view bytes);
//! Lower-case hex SHA-256 of a file's content; throws stiffpath::Error naming the path if unreadable.
std::string sha256_file_hex(const std::string& path);

}  // namespace stiffpath::core
