#pragma once
// A PNG file is a signature and a list of chunks, each with its length, type, data and a CRC-32
// of type and data, ending with IEND. Checking those before a decoder runs tells a cut or
// corrupted PNG apart at once, in kinray's own words: libpng otherwise prints its own
// "libpng error: ..." line on stderr before kinray's, and a flipped bit inside compressed data
// is only caught by the CRC.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace kinray {

/// What is wrong with the chunks of the PNG `bytes` (signature included), or nothing: a chunk
/// that runs past the end, a CRC that does not match, no IEND chunk.
[[nodiscard]] std::optional<std::string> png_chunk_problem(std::span<const uint8_t> bytes);

/// The same for the file at `path` (nothing when it cannot be read: the decoder's error stands).
[[nodiscard]] std::optional<std::string> png_file_chunk_problem(const std::filesystem::path& path);

}  // namespace kinray
