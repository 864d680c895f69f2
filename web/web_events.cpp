#include "web/web_events.h"

#include <algorithm>
#include <cmath>

namespace sonarloop::web {

std::uint8_t level_byte(float level_db) {
  const float u = (level_db - kDisplayMinDb) / (kDisplayMaxDb - kDisplayMinDb);
  if (!(u > 0.0f)) return 0;  // also NaN
  if (u >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(u * 255.0f));
}

void reduce_line(std::span<const float> levels, std::span<std::uint8_t> out) {
  const std::size_t n = levels.size();
  const std::size_t px = out.size();
  if (px == 0) return;
  if (n == 0) {
    std::fill(out.begin(), out.end(), std::uint8_t{0});
    return;
  }
  for (std::size_t i = 0; i < px; ++i) {
    if (n < px) {
      out[i] = level_byte(levels[std::min(n - 1, (2 * i + 1) * n / (2 * px))]);
      continue;
    }
    // mean power over the samples of pixel i: [i n / px, (i + 1) n / px)
    const std::size_t a = i * n / px;
    const std::size_t b = std::max(a + 1, (i + 1) * n / px);
    double power = 0.0;
    for (std::size_t k = a; k < b; ++k)
      power += std::pow(10.0, 0.1 * static_cast<double>(levels[k]));
    out[i] = level_byte(static_cast<float>(10.0 * std::log10(power / static_cast<double>(b - a))));
  }
}

std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string s;
  s.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) |
                            std::uint32_t{bytes[i + 2]};
    s += kAlphabet[(v >> 18) & 63];
    s += kAlphabet[(v >> 12) & 63];
    s += kAlphabet[(v >> 6) & 63];
    s += kAlphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (rest == 2) v |= std::uint32_t{bytes[i + 1]} << 8;
    s += kAlphabet[(v >> 18) & 63];
    s += kAlphabet[(v >> 12) & 63];
    s += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    s += '=';
  }
  return s;
}

std::string sse_event(std::string_view name, std::string_view data) {
  std::string s;
  s.reserve(name.size() + data.size() + 16);
  s.append("event: ").append(name).append("\ndata: ").append(data).append("\n\n");
  return s;
}

}  // namespace sonarloop::web
