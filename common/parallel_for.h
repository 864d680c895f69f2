#pragma once
// The project's one parallel loop, with one exception policy.
//
// parallel_for(n, workers, fn) runs fn(item, worker) for every item 0..n-1 on `workers` threads
// (clamped to [1, n]; the calling thread is worker 0, the others are started for the call and
// joined before it returns). Items are handed out one at a time in index order from a shared
// counter, so a slow item never holds up the others. Which worker runs an item is not fixed:
// fn must write only to its item's own output and its worker's own scratch, and then the results
// do not depend on the number of threads (the project's determinism rule, docs/design.md).
//
// Exceptions: the first one thrown by fn stops the other workers at their next item (items
// already started finish) and is rethrown on the calling thread once every worker has stopped;
// later ones are dropped. No exception escapes a worker thread (which would end the process).
//
// Used by every batch loop that splits independent items over threads: the seabed's tiles, the
// track renderer's pings, the emulator's start-up tiles, the lock-step mission's
// renders. Two kinds of parallel work are not batch loops and keep their own threads: the
// emulator's render queue (workers that live for a run and hand pings over at deadlines,
// emulator/render_queue.h) and the chip renderer's ordered hand-over (chips rendered ahead in a
// window and delivered in order, sim/render/chip_renderer.h).
#include <cstddef>
#include <functional>

namespace sonarloop {

void parallel_for(std::size_t n, int workers,
                  const std::function<void(std::size_t item, int worker)>& fn);

}  // namespace sonarloop
