#include "drivers/xtf/xtf_types.h"

#include <chrono>

namespace sonarloop::xtf {

std::size_t declared_channel_count(const XtfFileHeader& header) {
  return std::size_t{header.number_of_sonar_channels} + header.number_of_bathymetry_channels +
         header.number_of_snippet_channels + header.number_of_forward_look_arrays +
         header.number_of_echo_strength_channels + header.number_of_interferometry_channels;
}

std::size_t file_header_size_for(std::size_t channels) {
  if (channels <= kChanInfosInBaseHeader) return kFileHeaderSize;
  const std::size_t extra = channels - kChanInfosInBaseHeader;
  const std::size_t blocks = (extra + kChanInfosPerExtraBlock - 1) / kChanInfosPerExtraBlock;
  return kFileHeaderSize * (1 + blocks);
}

namespace {
constexpr std::int64_t kNsPerHsec = 10'000'000;  // 1/100 s
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::int64_t kSecondsPerDay = 86'400;
}  // namespace

std::optional<std::int64_t> time_utc_ns(const XtfPingHeader& h) {
  using namespace std::chrono;
  const year_month_day ymd{year{h.year}, month{h.month}, day{h.day}};
  if (!ymd.ok() || h.hour > 23 || h.minute > 59 || h.second > 60 || h.hseconds > 99) {
    return std::nullopt;
  }
  const std::int64_t days = sys_days{ymd}.time_since_epoch().count();
  const std::int64_t seconds =
      days * kSecondsPerDay + std::int64_t{h.hour} * 3600 + std::int64_t{h.minute} * 60 + h.second;
  return seconds * kNsPerSecond + std::int64_t{h.hseconds} * kNsPerHsec;
}

void set_time_utc_ns(XtfPingHeader& h, std::int64_t t_ns) {
  using namespace std::chrono;
  // floor to whole hundredths, then split into days and time of day
  std::int64_t hsec_total = t_ns / kNsPerHsec;
  if (t_ns % kNsPerHsec < 0) --hsec_total;
  constexpr std::int64_t kHsecPerDay = kSecondsPerDay * 100;
  std::int64_t days = hsec_total / kHsecPerDay;
  std::int64_t hsec_of_day = hsec_total % kHsecPerDay;
  if (hsec_of_day < 0) {
    hsec_of_day += kHsecPerDay;
    --days;
  }
  const sys_days sd{std::chrono::days{days}};
  const year_month_day ymd{sd};
  const int y = static_cast<int>(ymd.year());
  if (y < 0 || y > 9999) {
    throw std::invalid_argument("set_time_utc_ns: " + std::to_string(t_ns) +
                                " ns is outside the years 0-9999 an XTF ping header can hold");
  }
  const year_month_day jan1{ymd.year(), January, std::chrono::day{1}};
  const auto day_of_year = (sd - sys_days{jan1}).count() + 1;
  h.year = static_cast<std::uint16_t>(y);
  h.month = static_cast<std::uint8_t>(static_cast<unsigned>(ymd.month()));
  h.day = static_cast<std::uint8_t>(static_cast<unsigned>(ymd.day()));
  h.hour = static_cast<std::uint8_t>(hsec_of_day / 360'000);
  h.minute = static_cast<std::uint8_t>(hsec_of_day / 6'000 % 60);
  h.second = static_cast<std::uint8_t>(hsec_of_day / 100 % 60);
  h.hseconds = static_cast<std::uint8_t>(hsec_of_day % 100);
  h.julian_day = static_cast<std::uint16_t>(day_of_year);
}

const XtfChanInfo& chan_info_for(const XtfFileHeader& header, const XtfPingChannel& channel) {
  if (channel.channel_number >= header.chan_info.size()) {
    throw std::out_of_range("XTF ping channel has ChannelNumber " +
                            std::to_string(channel.channel_number) + " but the file header has " +
                            std::to_string(header.chan_info.size()) + " CHANINFO entries");
  }
  return header.chan_info[channel.channel_number];
}

}  // namespace sonarloop::xtf
