// Chips over MPI ranks (ranks/chip_ranks.h) in a world of one: the chip message round trip
// (every field, byte-exact), refused truncated and overlong messages, the dataset's job order,
// and render_chips_on_ranks equal to render::render_chips. The same path over two real ranks
// is tests/tools/mpi_cli_test.cpp.
#include "ranks/chip_ranks.h"

#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "ranks/mpi_world.h"

using namespace sonarloop;
using namespace sonarloop::render;

namespace {

ChipDatasetSpec small_spec(ChipKind kind) {
  ChipDatasetSpec s;
  s.seed = 11;
  s.kind = kind;
  s.classes = {targets::TargetType::kManta, targets::TargetType::kCylinder};
  s.seabeds = {builtin_dataset_seabed("flat"), builtin_dataset_seabed("ripples")};
  s.resolutions_m = {0.10, 0.20};
  s.sonar.name = "test";
  s.sonar.frequency_hz = 300e3;
  s.sonar.source_level_db = 210.0;
  s.sonar.array_length_m = 0.5;
  s.sonar.array_height_m = 0.006;
  s.sonar.depression_deg = 15.0;
  s.sonar.along_track = AlongTrackModel::kStrip;
  return s;
}

std::vector<std::byte> bytes_of(const ChipImage& c) {
  std::vector<std::byte> out;
  ranks::encode_chip(c, out);
  return out;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

TEST_CASE("chip_ranks: a world of one without mpirun") {
  ranks::mpi::start();  // not launched by mpirun: stays a world of one
  CHECK(ranks::mpi::size() == 1);
  CHECK(ranks::mpi::rank() == 0);
  CHECK(ranks::mpi::is_root());
  CHECK(ranks::ranks_note().empty());
  CHECK(ranks::mpi::default_threads() >= 1);
  CHECK(ranks::mpi::end_after_error(3) == 3);
  CHECK_FALSE(ranks::mpi::message_waiting(0));
}

TEST_CASE("chip_ranks: a chip survives the message round trip, every field") {
  for (ChipKind kind : {ChipKind::kHighlight, ChipKind::kShadow}) {
    const ChipRenderer r(small_spec(kind));
    const ChipImage c = r.render(5, 1);
    REQUIRE(!c.pixels.empty());
    REQUIRE(!c.truth.empty());
    const std::vector<std::byte> msg = bytes_of(c);
    const ChipImage d = ranks::decode_chip(msg);
    CHECK(d.params.index == c.params.index);
    CHECK(d.params.type == c.params.type);
    CHECK(d.params.seabed == c.params.seabed);
    CHECK(d.params.altitude_m == c.params.altitude_m);
    CHECK(d.params.ground_range_m == c.params.ground_range_m);
    CHECK(d.params.target_heading_deg == c.params.target_heading_deg);
    CHECK(d.params.track_heading_deg == c.params.track_heading_deg);
    CHECK(d.params.aspect_deg == c.params.aspect_deg);
    CHECK(d.params.side == c.params.side);
    CHECK(d.params.target_ne_m == c.params.target_ne_m);
    CHECK(d.params.along_offset == c.params.along_offset);
    CHECK(d.resolution == c.resolution);
    CHECK(d.resolution_m == c.resolution_m);
    CHECK(d.rows == c.rows);
    CHECK(d.cols == c.cols);
    CHECK(d.slant_range_m == c.slant_range_m);
    CHECK(d.range_start_m == c.range_start_m);
    CHECK(d.target_row == c.target_row);
    CHECK(d.target_col == c.target_col);
    CHECK(same_bytes(d.level_db, c.level_db));
    CHECK(same_bytes(d.pixels, c.pixels));
    CHECK(same_bytes(d.labels, c.labels));
    REQUIRE(d.truth.size() == c.truth.size());
    for (std::size_t k = 0; k < c.truth.size(); ++k) {
      CHECK(d.truth[k].highlight_first == c.truth[k].highlight_first);
      CHECK(d.truth[k].highlight_last == c.truth[k].highlight_last);
      CHECK(d.truth[k].shadow_first == c.truth[k].shadow_first);
      CHECK(d.truth[k].shadow_last == c.truth[k].shadow_last);
      CHECK(d.truth[k].energy == c.truth[k].energy);
    }
    CHECK(bytes_of(d) == msg);
  }
}

TEST_CASE("chip_ranks: truncated and overlong chip messages are refused") {
  const ChipRenderer r(small_spec(ChipKind::kHighlight));
  std::vector<std::byte> msg = bytes_of(r.render(2, 0));
  for (std::size_t cut : {std::size_t{0}, std::size_t{7}, msg.size() / 2, msg.size() - 1}) {
    INFO("cut at " << cut);
    CHECK_THROWS(ranks::decode_chip(std::span<const std::byte>(msg.data(), cut)));
  }
  msg.push_back(std::byte{0});
  CHECK_THROWS(ranks::decode_chip(msg));
  // an array length far beyond the message
  std::vector<std::byte> bogus(200, std::byte{0xff});
  CHECK_THROWS(ranks::decode_chip(bogus));
}

TEST_CASE("chip_ranks: the dataset's jobs run over indices, resolutions inner") {
  const auto jobs = ranks::dataset_jobs(3, 2);
  REQUIRE(jobs.size() == 6);
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    CHECK(jobs[j].index == j / 2);
    CHECK(jobs[j].resolution == static_cast<int>(j % 2));
  }
  CHECK(ranks::dataset_jobs(0, 3).empty());
}

TEST_CASE("chip_ranks: in a world of one, the same chips in the same order as render_chips") {
  const ChipRenderer r(small_spec(ChipKind::kHighlight));
  const auto jobs = ranks::dataset_jobs(6, 2);
  std::vector<std::vector<std::byte>> direct, ranks;
  render_chips(r, jobs, 2, [&](const ChipImage& c) { direct.push_back(bytes_of(c)); });
  const std::size_t n = ranks::render_chips_on_ranks(
      r, jobs, 2, [&](const ChipImage& c) { ranks.push_back(bytes_of(c)); });
  CHECK(n == jobs.size());
  CHECK(ranks == direct);
  // a stop request ends it early with a prefix
  std::vector<std::vector<std::byte>> part;
  const std::size_t got = ranks::render_chips_on_ranks(
      r, jobs, 1, [&](const ChipImage& c) { part.push_back(bytes_of(c)); },
      [&] { return part.size() >= 3; });
  CHECK(got == part.size());
  CHECK(got < jobs.size());
  CHECK(std::equal(part.begin(), part.end(), direct.begin()));
}
