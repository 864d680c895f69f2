#pragma once
// From the simulator's ping (render::PingLines) to XTF (drivers/xtf): the file header that
// describes the sonar, and one sonar packet per ping. Field semantics: docs/formats.md §1.
//
// Conventions
// - Channels: two sidescan channels, ChanInfo[0] = PORT (ChannelNumber 0), ChanInfo[1] =
//   STARBOARD (ChannelNumber 1); ChannelNumber is always the CHANINFO index
//   (docs/formats.md 1.6, 1.9) and the channel blocks of a ping come in the same order.
// - Samples: PingLines bin k covers slant range [k, k+1)·bin_size_m; it becomes sample k of
//   NumSamples = bins, quantised with render::quantise_line (TVG and gain applied, hence
//   ProcessingFlags = 4), SlantRange = bins·bin_size_m (range of the end of the last sample),
//   TimeDelay = 0. In the file the PORT samples are stored far range first (reversed), starboard
//   nadir first (docs/formats.md 1.7; xtf::stored_far_to_near).
// - Sample type (SonarDesc::sample_type) -> CHANINFO BytesPerSample / SampleFormat:
//   uint8 -> 1 / 8, uint16 -> 2 / 3, int16 -> 2 / 3, float32 -> 4 / 5 (IEEE float). X41 calls 8
//   and 3 "int8" and "int16"; readers (pyxtf) read them unsigned, and the samples are unsigned
//   envelope values (UniPolar = 1), full scale = VoltScale 5 V. int16 keeps them within 0 ..
//   32767, so a reader that takes format 3 as signed reads them right too (as the Sea Scan file
//   in tests/data/xtf). Float samples are amplitudes re full scale.
// - Sound speed: SoundVelocity = 750 m/s (Isis' one-way convention, docs/formats.md 1.5, 1.9) and
//   TimeDuration = SlantRange / 750, so that TimeDuration·SoundVelocity = SlantRange for any
//   reader; the real sound speed goes to ComputedSoundVelocity.
// - Frequency: CHANINFO Frequency (float) and ping-channel Frequency (WORD) in kHz, as the real
//   Iver / Sea Scan file does (tests/data/xtf: 600.0 and 600).
// - Navigation: NavUnits = 3, so Sensor/Ship Y = latitude and X = longitude in degrees (WGS84).
//   The vehicle is both "ship" and "sensor": Ship* = Sensor* (position, speed, heading), no
//   layback. Speeds in knots, attitude in degrees (pitch + nose up, roll + starboard down,
//   heading clockwise from north), depth and altitude in metres. FixTime and ComputerClock are
//   the ping time (the navigation is sampled at the ping). Time resolution is 1/100 s (HSeconds);
//   JulianDay is 1-based (xtf::set_time_utc_ns).
// - Altitude: a NaN altitude (no bottom) is written as SensorPrimaryAltitude = 0 and
//   GroundRange = 0; otherwise GroundRange = sqrt(SlantRange² − altitude²) (0 if negative).
// - Left zero (no source in the simulator, or meaningless here): ShipAltitude/ShipDepth (WORD
//   decimetres of the ship), EventNumber, OceanTide, CTD and magnetometer fields, SpeedLog, KP,
//   Layback (non-zero would make Isis move the sensor), Heave, Yaw, AttitudeTimeTag, gain codes,
//   BandWidth, FixedVSOP, Weight, offsets of the transducers.
#include <cstdint>
#include <string>

#include "common/geodesy.h"
#include "drivers/xtf/xtf_types.h"
#include "sim/render/ping_renderer.h"
#include "sim/render/sonar.h"
#include "sim/vehicle/nav_sensor.h"

namespace sonarloop::emulator {

// XTFFILEHEADER RecordingProgramName / Version. The version is the example of docs/formats.md 1.2
// (numeric, as readers parse it).
inline constexpr const char* kXtfRecordingProgramName = "SONARLP";
inline constexpr const char* kXtfRecordingProgramVersion = "223";

// XTFPINGHEADER.SoundVelocity: Isis' one-way (half) sound speed, m/s (docs/formats.md 1.5).
inline constexpr double kXtfSoundVelocityMps = 750.0;
// XTFPINGCHANHEADER.ProcessingFlags bit: TVG applied (docs/formats.md 1.6).
inline constexpr std::uint16_t kXtfProcessingTvg = 4;
// CHANINFO.VoltScale: volts of a full-scale sample.
inline constexpr float kXtfVoltScaleV = 5.0f;
// CHANINFO.CorrectionFlags 1: slant-range imagery.
inline constexpr std::uint16_t kXtfSlantRangeImagery = 1;

// ChannelNumber / ChanInfo index of the two sidescan channels.
inline constexpr std::uint16_t kXtfPortChannel = 0;
inline constexpr std::uint16_t kXtfStbdChannel = 1;

// Metres per second -> knots (1 international nautical mile = 1852 m).
inline constexpr double kKnotsPerMps = 3600.0 / 1852.0;

// Navigation of one ping, in the units XTF stores (degrees) except speeds and lengths (SI).
struct PingNav {
  std::int64_t time_utc_ns = 0;  // ping time, ns since 1970-01-01T00:00:00Z
  GeoPoint sensor;               // sonar position, WGS84
  double heading_deg = 0.0;      // clockwise from north, [0, 360)
  double pitch_deg = 0.0;        // + nose up
  double roll_deg = 0.0;         // + starboard down
  double depth_m = 0.0;          // below the surface, + down
  double altitude_m = 0.0;       // above the seabed; NaN = unknown
  double speed_m_s = 0.0;        // over ground
  std::uint32_t ping_number = 0;
};

// The navigation a ping records: the navigation solution at the ping's time (`nav`), the
// sensor's position through `ltp`, angles in degrees; where the solution has no altitude (NaN),
// the one the renderer found below the sonar (`rendered_altitude_m`, PingLines::altitude_m).
PingNav ping_nav_of(const vehicle::NavSolution& nav, const LocalTangentPlane& ltp,
                    std::int64_t time_utc_ns, double rendered_altitude_m,
                    std::uint32_t ping_number);

// The file header for a sonar: 2 channels (PORT, STARBOARD) described from `sonar` (frequency,
// beam widths, depression, sample type, bins). `sonar_name` (16 bytes) and `note` (64 bytes) are
// cut to their fields at a UTF-8 character boundary.
xtf::XtfFileHeader make_xtf_file_header(const render::SonarSetup& sonar,
                                        const std::string& sonar_name, const std::string& note);

// Fills `out` with the ping: every field of the ping header and of both channel headers is
// rewritten (unused ones zeroed), and the samples are quantised into out's own sample buffers.
// Does not allocate when `out` already holds two channels whose sample vectors have the sonar's
// sample type and at least `bins` capacity (i.e. from the second call on).
// Throws std::invalid_argument if `header` is not a header of make_xtf_file_header for this
// sample type (channel types / BytesPerSample), or if the lines do not have sonar.bins bins;
// std::invalid_argument from xtf::set_time_utc_ns for a time outside years 0-9999.
void make_xtf_ping(const render::SonarSetup& sonar, const xtf::XtfFileHeader& header,
                   const render::PingLines& lines, const PingNav& nav, xtf::XtfPing& out);

}  // namespace sonarloop::emulator
