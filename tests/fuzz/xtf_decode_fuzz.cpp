// XTF decoders (drivers/xtf/xtf_codec.h): the file header, datagram classification and the ping
// packet decoder, on the bytes of one datagram.
#include <exception>

#include "drivers/xtf/xtf_codec.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto in = fuzz::bytes(data, size);
  (void)xtf::classify_datagram(in);
  (void)xtf::peek_packet(in);
  xtf::XtfFileHeader header;
  try {
    header = xtf::decode_file_header(in);
  } catch (const std::exception&) {
    // a default two-channel sidescan header, so that the ping decoder runs anyway
    header.number_of_sonar_channels = 2;
    header.chan_info.resize(2);
    header.chan_info[1].type_of_channel = xtf::kChannelStbd;
    header.chan_info[1].sub_channel_number = 1;
  }
  try {
    (void)xtf::decode_ping(in, header);
  } catch (const std::exception&) {
  }
  return 0;
}
