// Sharing views over the ranks, in a job of one process: every view and row is this
// process's, nothing is banded, and the exchanges hand the buffers back unchanged. The
// shares and exchanges of several ranks are checked under mpirun (CTest mpi_render).
#include "scene/view_sharing.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(ViewSharing, OneProcessRendersEveryViewWhole) {
  ASSERT_FALSE(cluster::distributed());
  for (size_t views : {size_t(0), size_t(1), size_t(7)}) {
    ViewShare share(views, /*allowBands=*/true);
    EXPECT_FALSE(share.banded());
    EXPECT_EQ(share.myCount(), views);
    for (size_t v = 0; v < views; ++v) {
      EXPECT_TRUE(share.mine(v));
      EXPECT_EQ(share.owner(v), 0);
    }
    cluster::Share rows = share.myRows(48);
    EXPECT_EQ(rows.begin, 0);
    EXPECT_EQ(rows.end, 48);
    EXPECT_EQ(share.progressLabel("render"), "render");
  }
}

TEST(ViewSharing, ExchangesInAJobOfOneKeepTheBuffers) {
  ViewBuffers buffers = ViewBuffers::allocate(5, 3);
  buffers[Buffer::Depth].at(4, 2) = 7.5f;
  EXPECT_EQ(joinBandsOnRoot(buffers)[Buffer::Depth].pixels, buffers[Buffer::Depth].pixels);
  EXPECT_EQ(sendViewToRoot(buffers, 0)[Buffer::Depth].pixels, buffers[Buffer::Depth].pixels);
}

}  // namespace
}  // namespace glint
