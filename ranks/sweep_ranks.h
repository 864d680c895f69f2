#pragma once
// `sonarloop sweep` over the ranks of an MPI job (ranks/chip_ranks.h): rank 0 runs the sweep as
// in one process (training, scoring, files, output) and takes every chip it needs from
// render_sweep_chips; the other ranks run serve_sweep, which makes the same render calls in the
// same order, so that each renders its share of every chip set. The order exists once: per
// experiment, per render group (study::render_groups), per resolution slot, the group's chip sets
// in study::group_chip_sets' order, which rank 0 takes one by one and checks (ranks/sweep_run.cpp,
// SlotSets); the call fingerprints of chip_ranks.h turn a mismatch into an error, and
// tests/tools/mpi_cli_test.cpp checks the files.
#include <cstddef>
#include <functional>
#include <vector>

#include "sim/render/chip_renderer.h"
#include "study/sweep.h"

namespace sonarloop::ranks {

// Chips 0 .. count-1 at resolution slot `slot`, over the ranks, handed to `sink` on rank 0 in
// index order; polls `stop` (may be empty; the command's Ctrl-C flag). Returns the number handed
// over, on every rank.
std::size_t render_sweep_chips(const render::ChipRenderer& r, int slot, std::size_t count,
                               int threads,
                               const std::function<void(const render::ChipImage&)>& sink,
                               const std::function<bool()>& stop);

// The other ranks' side of a sweep: renders this rank's share of every chip set of
// `experiments`, in study::group_chip_sets' order. Returns false when rank 0 stopped early.
bool serve_sweep(const std::vector<study::SweepExperiment>& experiments,
                 const study::SweepSettings& settings, int threads,
                 const std::function<bool()>& stop);

}  // namespace sonarloop::ranks
