#pragma once
// The classifier's model file (.slpca): a versioned little-endian binary format.
//
// Version 6 layout (all integers unsigned little-endian, floats IEEE 754 little-endian). Version
// 5 is the same without the views record (read as none); version 4 also without the detector
// rules record (read as none: the detector's own options);
// version 3 without the clutter flag (flags bit 1) and the gates; version 2 without the class
// height (its flags byte is 0); version 1 also lacks the pre-processing record (read as no
// pre-processing) and the reject and typical distances. Older versions are read with every class's
// height unknown (the tools then fill the heights of the simulator's target classes,
// fill_legacy_class_heights, tools/chip_options.h); mine_like was stored by every version.
//
//   header, 36 bytes
//     0   u8[5]  magic "SLPCA"
//     5   u8     0 (reserved)
//     6   u16    format version (6)
//     8   u32    chip width (pixels)
//    12   u32    chip height (pixels)                      n = width * height
//    16   u32    p, the requested subspace dimension
//    20   u32    aspect sectors N
//    24   u32    class count C (>= 1)
//    28   u32    group count G (0, or 2: "mine" then "non_mine", Section 4.1.2)
//    32   u32    0 (reserved)
//   pre-processing record, 24 bytes (version 2; atr/chip_preprocess.h)
//    36   f64    crop fraction (0, 1]
//    44   u32    multilook window k (odd)
//    48   u8     levels mode (0 db, 1 above_seabed, 2 below_seabed, 3 three_level)
//    49   u8[3]  0 (reserved)
//    52   f64    three-level threshold (dB)
//   C class records, then G group records, each:
//     u16    name length L (1 to 255), then L bytes of name (UTF-8, no terminator)
//     u8     mine_like (0 or 1)
//     u8     flags (version 3; 0 before): bit 0 set when the class height is known; bit 1
//            (version 4) set for a clutter class (atr/subspace_classifier.h ClassMetadata)
//     u32    subspace count S (>= 1)
//     f32    reject distance (version 2): open-set threshold, +infinity for none
//     f32    typical distance (version 2): median cross-validated distance, 0 for none
//     f64    height_m (version 3): the class's object height above the seabed (0 to 100 m)
//            when flag bit 0 is set, else 0 (unknown)
//     S subspace records:
//       f64      aspect_min_deg, f64 aspect_max_deg   the sector [min, max), within [0, 360]
//       u32      train_count k (>= 1)
//       u32      rank r (<= p, <= k - 1)
//       f64[r]   Gram eigenvalues, descending
//       f32[n]   mean image mu, row-major pixel order (eq. 8); n is the pre-processed
//                (cropped) chip's pixel count
//       f32[r*n] basis U, column by column: the n values of eigenvector 0, then 1, ...
//   gates (version 4; atr/contact_gate.h)
//     u32    gate count (0 to 2), then each gate:
//       u8     stage (0 detection, 1 classification; at most one of each)
//       u8     form (0 linear, 1 quadratic), u8[2] 0
//       u32    feature count n (the stage's: 11 detection, 15 classification)
//       f64    threshold (a candidate passes when p >= it), f64 bias
//       f64[n] feature means, f64[n] feature scales, f64[T] weights (T = n linear, n + n(n+1)/2
//              quadratic: atr/logistic_gate.h)
//   detector rules (version 5; atr/subspace_classifier.h DetectorRules)
//     u8     1 when recorded (then the two fields follow), 0 for none; u8[3] 0
//     u32    min_pings (1 to 1000), f64 min_along_m (0 to 100)
//   views (version 6; atr/subspace_classifier.h ModelView, "Fused readings")
//     u32    view count V (0 to 3), then each view:
//       pre-processing record, 24 bytes, as above (its crop fraction the model's)
//       C records, one per class in the model's order (its name and flags are the class's):
//         u32 subspace count S (>= 1), then S subspace records as above
//   trailer
//     u32    CRC-32 (IEEE 802.3 polynomial, as zlib's crc32) of every preceding byte
//
// A 64 x 64 model with 4 classes, one subspace each and p = 20 takes 4 * 21 * 4096 * 4 B = 1.4 MB.
// Loading checks everything: magic, version, sizes and counts against sane limits, the checksum,
// truncation, trailing bytes, then validate_model() (finite values, orthonormal bases, ranks).
// Errors are std::runtime_error naming the file, the byte offset and what was expected.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "atr/subspace_classifier.h"
#include "drivers/io/crc32.h"

namespace sonarloop::atr {

inline constexpr std::uint16_t kModelFileVersion = 6;
inline constexpr char kModelFileMagic[5] = {'S', 'L', 'P', 'C', 'A'};

// The file's bytes for a (valid) model. Throws std::runtime_error if validate_model() fails.
std::vector<std::uint8_t> encode_model(const Model& m);
// Parses a model from bytes; `name` (a file name) prefixes error messages. `version`, when
// given, receives the file's format version (1 to kModelFileVersion).
Model decode_model(std::span<const std::uint8_t> bytes, const std::string& name = "model",
                   std::uint16_t* version = nullptr);

void save_model(const Model& m, const std::string& path);
// The largest model file load_model opens (a regular file: drivers/io/input_file.h): 1 GB,
// hundreds of times a real model (the default model is 2.9 MB).
inline constexpr std::uint64_t kMaxModelFileBytes = std::uint64_t{1} << 30;
Model load_model(const std::string& path, std::uint16_t* version = nullptr);

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320, initial and final XOR 0xFFFFFFFF;
// drivers/io/crc32.h).
using io::crc32;

}  // namespace sonarloop::atr
