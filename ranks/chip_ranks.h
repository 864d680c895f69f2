#pragma once
// Chips rendered by all the ranks of an MPI job (ranks/mpi_world.h) and handed over on rank 0 in
// job order, exactly as render::render_chips does in one process: `sonarloop dataset` and
// `sonarloop sweep` on a cluster.
//
// Sharing: job j of a call is rendered by rank j mod size (each rank with its own threads);
// chip i depends only on (seed, i) (sim/render/chip_renderer.h), so which rank renders it
// changes no byte. The other ranks send their chips to rank 0 one at a time, each send waiting
// until rank 0 takes it, so a rank holds at most its render window of chips (a few per thread)
// and rank 0 one chip per rank: memory does not grow with the job count.
//
// Protocol of one call (every rank calls render_chips_on_ranks with the same jobs):
//   rank 0 -> each rank   kTagCall    the call's job count and fingerprint (checked: ranks that
//                                     fell out of step fail instead of mixing datasets)
//   rank r -> rank 0      kTagChip    its chips, in job order
//   rank r -> rank 0      kTagEnd     no more chips (all done, or stopped early)
//   rank 0 -> each rank   kTagFinish  the number of chips handed to rank 0's sink
// Rank 0 stops early when `stop` says so or a rank ended early (Ctrl-C reaches every rank);
// it then tells every rank to finish and throws away the chips still on their way.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "sim/render/chip_renderer.h"

namespace sonarloop::ranks {

// Renders `jobs` over the ranks and hands every chip to `sink` on rank 0, in job order; the
// sink never runs on the other ranks. Every rank must make the same calls with the same jobs
// (a collective call). `stop` (optional) is polled between chips on every rank. Returns, on
// every rank, the number of chips handed to rank 0's sink (jobs[0, n) exactly). In a world of
// one this is render::render_chips. Throws std::logic_error when the ranks are out of step;
// exceptions of the renderer or the sink are rethrown on the rank that raised them.
std::size_t render_chips_on_ranks(const render::ChipRenderer& renderer,
                                  std::span<const render::ChipJob> jobs, int threads,
                                  const std::function<void(const render::ChipImage&)>& sink,
                                  const std::function<bool()>& stop = {});

// The jobs of `sonarloop dataset`: chips 0 .. count-1, each at every resolution slot in turn.
std::vector<render::ChipJob> dataset_jobs(std::uint64_t count, std::size_t resolutions);

// The other ranks' side of `sonarloop dataset`: renders this rank's share of dataset_jobs(count,
// resolutions) of `spec` while rank 0 writes the files. Returns the exit code: 0, or 130 when
// stopped early.
int serve_dataset(const render::ChipDatasetSpec& spec, std::uint64_t count, int threads,
                  const std::function<bool()>& stop);

// A chip as the bytes of a message and back: every field, native byte order (the ranks of a job
// run the same binary on the same kind of machine). decode_chip throws std::runtime_error for a
// truncated or overlong message.
void encode_chip(const render::ChipImage& chip, std::vector<std::byte>& out);
render::ChipImage decode_chip(std::span<const std::byte> bytes);

// " on N ranks" for a job of several ranks, "" otherwise: for the commands' summary lines.
std::string ranks_note();

}  // namespace sonarloop::ranks
