#pragma once
// File reading and crash-safe writing for the command line.

#include <string>

namespace avk::server {

// Reads a whole file ("-" is standard input); throws std::runtime_error naming the path.
std::string read_file(const std::string& path, std::istream& stdin_stream);

// Writes through a temporary file and a rename, so an existing file is either replaced whole or
// left as it was: an interrupted export never leaves half a CKT file behind.
void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace avk::server
