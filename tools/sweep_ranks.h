#pragma once
// `sonarloop sweep` over the ranks of an MPI job (ranks/chip_ranks.h): rank 0 runs the sweep as
// in one process (training, scoring, files, output) and takes every chip it needs from
// render_sweep_chips; the other ranks run serve_sweep, which makes the same render calls in the
// same order, so that each renders its share of every chip set. The order is tools/sweep_run.cpp's:
// per experiment, per render group (study::render_groups), per resolution slot, the training chips
// then the test chips, then the test chips' other looks (--looks) (fusion: highlight then shadow
// training chips, highlight then shadow test chips). A change of that order must be made in both
// places; the call fingerprints of chip_ranks.h turn a mismatch into an error, and
// tests/tools/mpi_cli_test.cpp checks the files.
#include <cstddef>
#include <functional>
#include <vector>

#include "sim/render/chip_renderer.h"
#include "study/sweep.h"

namespace sonarloop::tools {

// Chips 0 .. count-1 at resolution slot `slot`, over the ranks, handed to `sink` on rank 0 in
// index order; polls the Ctrl-C stop flag. Returns the number handed over, on every rank.
std::size_t render_sweep_chips(const render::ChipRenderer& r, int slot, std::size_t count,
                               int threads,
                               const std::function<void(const render::ChipImage&)>& sink);

// The other ranks' side of a sweep: renders this rank's share of every chip set of
// `experiments`, in tools/sweep_run.cpp's order. Returns false when rank 0 stopped early.
bool serve_sweep(const std::vector<study::SweepExperiment>& experiments,
                 const study::SweepSettings& settings, int threads);

}  // namespace sonarloop::tools
