// How the ranks of an MPI job share the views of a render, an evaluation or a synthesis,
// and how rendered buffers reach rank 0, which writes what is one file for the whole job
// (docs/cluster.md). In a job of one process every view is this process's and nothing moves.
#pragma once

#include <cstddef>
#include <string>

#include "core/cluster.h"
#include "scene/buffers.h"

namespace glint {

// Views go round-robin, view v to rank v mod N: the counts differ by at most one as with
// contiguous ranges, and views whose cost drifts along the list (an orbit passing a complex
// object, the test views of a synthesis rendered at more samples after the training ones)
// are spread over every rank instead of landing on one. With fewer views than ranks and
// bands allowed, every rank renders a band of rows of every view instead, and rank 0 joins
// the bands (joinBandsOnRoot): a single large image uses the whole job.
class ViewShare {
 public:
  ViewShare(size_t views, bool allowBands);
  // Every rank renders its band of every view.
  bool banded() const { return banded_; }
  // Whether this rank renders view v (whole, or its band when banded).
  bool mine(size_t v) const;
  // The rank that renders view v whole (when not banded).
  int owner(size_t v) const { return int(v % size_t(cluster::size())); }
  // The views this rank renders, for its progress bar.
  size_t myCount() const;
  // The rows of an image `height` rows tall that this rank renders: its contiguous band when
  // banded, else every row.
  cluster::Share myRows(int height) const;
  // "render" -> "render (rank 0's share of 2 ranks)" in a job of several, as it is rank 0's
  // progress that the job shows.
  std::string progressLabel(const std::string& label) const;

 private:
  size_t views_ = 0;
  bool banded_ = false;
};

// Every rank's band of one view (rows in rank order, as ViewShare::myRows hands them out),
// joined into the whole view on rank 0; the other ranks get empty buffers. A buffer empty in
// any band is empty in the result. Collective: every rank calls it for the same view.
ViewBuffers joinBandsOnRoot(const ViewBuffers& band);

// The buffers that rank `owner` rendered, on rank 0 (the other ranks pass anything and get
// empty buffers; on rank 0 when it is the owner, its own). Collective.
ViewBuffers sendViewToRoot(const ViewBuffers& buffers, int owner);

}  // namespace glint
