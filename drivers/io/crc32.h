#pragma once
// CRC-32 as zlib and IEEE 802.3 compute it (reflected polynomial 0xEDB88320, initial value and
// final XOR 0xFFFFFFFF; the check value of "123456789" is 0xCBF43926): the model file's trailer
// (atr/model_file.h) and MCAP's data, chunk and summary checksums (drivers/mcap/mcap_writer.h).
#include <cstdint>
#include <span>

namespace sonarloop::io {

// The CRC-32 of `bytes`.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

// Incremental: crc32_update(crc32_update(0, a), b) == crc32(a then b).
std::uint32_t crc32_update(std::uint32_t crc, std::span<const std::uint8_t> bytes);

}  // namespace sonarloop::io
