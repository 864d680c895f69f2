#pragma once
// `sonarloop run --record DIR`: what was published, as files.
//
//   DIR/pings.xtf   the XTF file header, then every ping packet sent, byte for byte the UDP
//                   datagrams (so "file header + ping datagrams" of the stream == this file).
//                   XtfWriter appends each packet with one write(2): after any stop the file
//                   holds whole packets only and is a valid XTF file.
//   DIR/nav.log     every NMEA 2000 frame published, candump format without comment lines
//                   (drivers/can/candump_log.h; python-can's CanutilsLogReader reads it), each
//                   stamped with its sample time epoch + t (not the moment it left the process,
//                   so the log is reproducible and replays without jitter).
//   DIR/truth.csv   one row per ping in pings.xtf: what it was rendered from. Columns:
//       ping           XTF PingNumber (k: ping time = k x ping period)
//       t_s            ping time since the mission start, s
//       time_utc_ns    epoch + t, ns since 1970 (the XTF ping's time, which has 10 ms steps)
//       north_m, east_m, depth_m          true sonar position, world frame (sim/frames.h)
//       heading_deg, pitch_deg, roll_deg  true attitude (heading clockwise from north in
//                                         [0, 360), pitch + nose up, roll + starboard down)
//       altitude_m     height above the seabed at nadir as the renderer saw it (empty: none)
//       latitude_deg, longitude_deg       true position, WGS84
//       speed_m_s      true speed over ground
//       pose           "trajectory", or "external" (--pose-from)
//     (The XTF ping carries the navigation system's view, with its errors; truth.csv the truth.)
//
// nav.log and truth.csv are written one whole line per write(2) (io::LineFile), pings.xtf one
// whole packet per write: after a crash or SIGKILL every file ends with a whole line / packet.
//
// Errors: a directory or file that cannot be created throws std::runtime_error naming it. A
// write error while recording (a full disk, say) does not stop the run: the recording stops
// there, every file keeping its whole lines and packets, and error() says which file failed and
// why ("... ENOSPC: the disk is full"). close() is called on normal end and after SIGINT/SIGTERM.
#include <cstdio>
#include <memory>
#include <string>

#include "drivers/can/candump_log.h"
#include "drivers/io/line_file.h"
#include "drivers/xtf/xtf_file.h"
#include "emulator/render_queue.h"

namespace sonarloop::emulator {

class Recording {
 public:
  Recording(const std::string& dir, const xtf::XtfFileHeader& header,
            const std::string& can_channel = "vcan0");
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  // Appends a sent ping: its packet to pings.xtf and its row to truth.csv. No allocation. After
  // a write error (error() set) it does nothing.
  void write_ping(const PingSlot& slot);
  // Appends a navigation frame to nav.log (t_ns: ns since the UNIX epoch). After a write error
  // it does nothing.
  void write_nav(const can::CanFrame& frame, std::int64_t t_ns);
  // Closes all three files (idempotent). Throws std::runtime_error on I/O errors.
  void close();
  // The write error that stopped the recording, naming the file ("" while it records).
  const std::string& error() const { return error_; }

  const std::string& dir() const { return dir_; }
  std::uint64_t pings() const { return pings_; }

 private:
  std::string dir_;
  std::unique_ptr<xtf::XtfWriter> xtf_;
  std::unique_ptr<can::CandumpLogWriter> nav_log_;
  std::unique_ptr<io::LineFile> truth_;
  std::uint64_t pings_ = 0;
  std::string error_;
};

}  // namespace sonarloop::emulator
