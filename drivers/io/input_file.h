#pragma once
// What sonarloop reads as input (models, chips, scenarios, recordings) must be a regular file of
// a sane size. A FIFO would block the reader for ever, /dev/zero or /dev/urandom would feed it
// until memory runs out, a folder fails deep inside a stream library with a message that does
// not name it. check_input_file says which, with the path, before anything is opened for
// reading. (A file swapped for another between the check and the open is not guarded against:
// the inputs are the user's own files, not an attacker racing the reader.)
#include <cstdint>
#include <string>
#include <string_view>

namespace sonarloop::io {

// Checks that `path` (symlinks followed) is a regular file of at most max_bytes; returns its
// size. Throws std::runtime_error naming `what` and the path otherwise:
//   "model file '/dev/zero': not a regular file (a character device)"
//   "chip 'x.png': cannot open: Too many levels of symbolic links"
//   "model file 'big.slpca': 3.2 GB, more than the 1.0 GB a model file may be"
std::uint64_t check_input_file(const std::string& path, std::string_view what,
                               std::uint64_t max_bytes = UINT64_MAX);

// What a file of this st_mode is, in words ("a FIFO", "a directory", "a character device", ...).
std::string file_type_name(unsigned mode);

}  // namespace sonarloop::io
