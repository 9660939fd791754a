// k-nearest-neighbour search in a k-d tree. A k-d tree rather than a uniform grid: a grid's
// query cost grows with the cube of the gap (in cells) to a point's nearest neighbours, so
// a few isolated far points (distant background depth) would dominate the run time, and
// its cell size needs tuning; the tree adapts to any distribution.
#include "train/nearest_neighbours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"

namespace glint {

namespace {

// Leaves small enough that scanning one costs about as much as descending one more level.
constexpr uint32_t kLeafSize = 8;

class KdTree {
 public:
  explicit KdTree(const std::vector<Vec3f>& points) : points_(points), order_(points.size()) {
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.reserve(2 * points.size() / kLeafSize + 1);
    build(0, uint32_t(points.size()));
  }

  // Offers every point except `self` that could be among the k nearest to p.
  template <typename List>
  void search(const Vec3d& p, uint32_t self, List& nearest, uint32_t node = 0) const {
    const Node& n = nodes_[node];
    if (n.axis < 0) {
      for (uint32_t i = n.begin; i < n.end; ++i) {
        uint32_t j = order_[i];
        if (j == self) continue;
        Vec3d d = Vec3d(points_[j]) - p;
        nearest.offer(dot(d, d));
      }
      return;
    }
    // The left child holds coordinates <= split, the right >= split, so the far child's
    // points are at least |diff| away.
    double diff = p[n.axis] - double(n.split);
    uint32_t nearChild = diff < 0.0 ? n.left : n.right;
    uint32_t farChild = diff < 0.0 ? n.right : n.left;
    search(p, self, nearest, nearChild);
    if (!nearest.full() || diff * diff < nearest.worst()) search(p, self, nearest, farChild);
  }

 private:
  struct Node {
    uint32_t begin = 0, end = 0;  // range of order_ covered
    int axis = -1;                // -1 for a leaf
    float split = 0.0f;
    uint32_t left = 0, right = 0;
  };

  // Splits at the median of the axis of largest spread; returns the node's index.
  uint32_t build(uint32_t begin, uint32_t end) {
    uint32_t index = uint32_t(nodes_.size());
    nodes_.push_back(Node{begin, end});
    if (end - begin <= kLeafSize) return index;
    Vec3f lower = points_[order_[begin]], upper = lower;
    for (uint32_t i = begin; i < end; ++i) {
      lower = min(lower, points_[order_[i]]);
      upper = max(upper, points_[order_[i]]);
    }
    Vec3f spread = upper - lower;
    int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    if (spread[axis] <= 0.0f) return index;  // all points coincide: keep them in one leaf
    uint32_t mid = begin + (end - begin) / 2;
    // Ties broken by index: a total order, so the tree depends only on the input.
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](uint32_t a, uint32_t b) {
      float pa = points_[a][axis], pb = points_[b][axis];
      return pa < pb || (pa == pb && a < b);
    });
    float split = points_[order_[mid]][axis];
    uint32_t left = build(begin, mid);
    uint32_t right = build(mid, end);
    Node& node = nodes_[index];
    node.axis = axis;
    node.split = split;
    node.left = left;
    node.right = right;
    return index;
  }

  const std::vector<Vec3f>& points_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

// The k smallest squared distances offered so far, ascending.
class NearestList {
 public:
  explicit NearestList(int k) : k_(k) { best_.reserve(size_t(k) + 1); }
  void offer(double d2) {
    if (full() && d2 >= best_.back()) return;
    best_.insert(std::upper_bound(best_.begin(), best_.end(), d2), d2);
    if (int(best_.size()) > k_) best_.pop_back();
  }
  bool full() const { return int(best_.size()) == k_; }
  double worst() const { return best_.back(); }
  double meanDistance() const {
    double sum = 0.0;
    for (double d2 : best_) sum += std::sqrt(d2);
    return best_.empty() ? 0.0 : sum / double(best_.size());
  }

 private:
  int k_;
  std::vector<double> best_;
};

}  // namespace

std::vector<float> meanNeighbourDistances(const std::vector<Vec3f>& points, int k) {
  GLINT_CHECK(k >= 1, "meanNeighbourDistances: k must be positive");
  GLINT_CHECK(points.size() < (size_t(1) << 32), "meanNeighbourDistances: too many points for 32-bit indices");
  std::vector<float> result(points.size(), 0.0f);
  if (points.size() < 2) return result;
  const int wanted = int(std::min<size_t>(size_t(k), points.size() - 1));
  const KdTree tree(points);
  // The k nearest distances are a property of the point set, not of the search order, so
  // each point's result is the same whichever thread computes it.
  parallelFor(int64_t(points.size()), 512, [&](int64_t i) {
    NearestList nearest(wanted);
    tree.search(Vec3d(points[size_t(i)]), uint32_t(i), nearest);
    result[size_t(i)] = float(nearest.meanDistance());
  });
  return result;
}

}  // namespace glint
