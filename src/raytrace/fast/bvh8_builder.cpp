// Binned-SAH construction of the 8-wide BVH: per-Gaussian proxy boxes, top-down splits,
// parallel subtrees, then the leaves' kernel data.
#include "raytrace/fast/bvh8_builder.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "core/parallel.h"

#ifdef __SSE4_1__
#include <immintrin.h>
#endif

namespace glint {
namespace {

constexpr int kMaxBins = 32;
constexpr uint32_t kMaxLeafSize = kMaxLeafBlocks * kBvhWidth;
// Ranges at least this large bin their primitives in parallel...
constexpr uint32_t kParallelBinning = 1u << 16;
// ...and build the subtrees of their children in parallel.
constexpr uint32_t kParallelSubtrees = 1u << 13;
// Below this many wide levels splits follow the SAH; deeper ones split at the median
// along the widest axis, which bounds the depth (and the traversal stack) even for
// degenerate scenes such as many Gaussians at one point.
constexpr int kSahDepth = 24;

// A Gaussian's proxy box; the Gaussian's index rides (as a bit pattern) in the fourth lane
// of the lower corner, which is never read as a coordinate, so a reference is 32 bytes
// and box operations stay 4-wide.
struct PrimRef {
  Box3 box;

  uint32_t id() const {
    uint32_t i;
    std::memcpy(&i, &box.lower[3], sizeof(i));
    return i;
  }
  void setId(uint32_t i) { std::memcpy(&box.lower[3], &i, sizeof(i)); }
  // Twice the box centre (the factor 2 cancels everywhere it is used).
  float centroid(int a) const { return box.lower[a] + box.upper[a]; }
  Box3 centroidBox() const {
    Box3 c;
    for (int a = 0; a < 4; ++a) c.lower[a] = c.upper[a] = box.lower[a] + box.upper[a];
    return c;
  }
};

struct Range {
  uint32_t begin = 0, end = 0;
  Box3 bounds;     // of the primitives' boxes
  Box3 centroids;  // of their (doubled) centres
  uint32_t size() const { return end - begin; }
};

struct LeafRange {
  uint32_t begin, end;
};

// While building, a leaf child refers to its LeafRange (~index); the final codes with
// block numbers are set once every leaf is known.
int32_t leafRef(uint32_t leaf) { return ~int32_t(leaf); }
uint32_t leafIndex(int32_t code) { return uint32_t(~code); }

// A subtree under construction: node indices and leaf indices are local to it.
struct Subtree {
  std::vector<Bvh8Node> nodes;
  std::vector<LeafRange> leaves;
  int depth = 0;  // inner-node levels from the root of the whole tree down to its deepest node
};

// Bounds and centre bounds of refs[begin, end), in parallel for large ranges.
void computeRangeBounds(const PrimRef* refs, Range* r) {
  r->bounds = Box3();
  r->centroids = Box3();
  std::mutex mutex;
  parallelForChunks(int64_t(r->size()), kParallelBinning / 4, [&](int64_t b, int64_t e) {
    Box3 bounds, centroids;
    for (int64_t i = b; i < e; ++i) {
      bounds.grow(refs[r->begin + i].box);
      centroids.grow(refs[r->begin + i].centroidBox());
    }
    std::lock_guard<std::mutex> lock(mutex);
    r->bounds.grow(bounds);
    r->centroids.grow(centroids);
  });
}

// Maps centres to kBins equal bins per axis.
template <int kBins>
struct BinMapping {
  alignas(16) float origin[4];
  alignas(16) float scale[4];  // 0 on axes where every centre coincides

  explicit BinMapping(const Box3& centroids) {
    for (int a = 0; a < 4; ++a) {
      float extent = centroids.upper[a] - centroids.lower[a];
      origin[a] = centroids.lower[a];
      scale[a] = a < 3 && extent > 0.0f ? float(kBins) * 0.99999f / extent : 0.0f;
    }
  }
  int bin(const PrimRef& r, int a) const {
    int b = int((r.centroid(a) - origin[a]) * scale[a]);
    return std::clamp(b, 0, kBins - 1);
  }
  // The bins of all three axes at once.
  void bins(const PrimRef& r, int out[4]) const {
#ifdef __SSE4_1__
    __m128 c = _mm_add_ps(_mm_load_ps(r.box.lower), _mm_load_ps(r.box.upper));
    __m128i b = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(c, _mm_load_ps(origin)), _mm_load_ps(scale)));
    b = _mm_min_epi32(_mm_max_epi32(b, _mm_setzero_si128()), _mm_set1_epi32(kBins - 1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), b);
#else
    for (int a = 0; a < 3; ++a) out[a] = bin(r, a);
#endif
  }
};

template <int kBins>
struct Bins {
  Box3 box[3][kBins];        // bounds of the primitives in each bin
  Box3 centroids[3][kBins];  // bounds of their centres
  uint32_t count[3][kBins] = {};

  void add(const PrimRef* refs, uint32_t begin, uint32_t end, const BinMapping<kBins>& map) {
    for (uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs[i];
      Box3 c = r.centroidBox();
      int b[4];
      map.bins(r, b);
      for (int a = 0; a < 3; ++a) {
        box[a][b[a]].grow(r.box);
        centroids[a][b[a]].grow(c);
        ++count[a][b[a]];
      }
    }
  }
  void merge(const Bins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < kBins; ++b) {
        box[a][b].grow(o.box[a][b]);
        centroids[a][b].grow(o.centroids[a][b]);
        count[a][b] += o.count[a][b];
      }
  }
};

// Splits r at the bin boundary of lowest SAH cost; returns false when no boundary has
// primitives on both sides (every centre in one bin).
template <int kBins>
bool splitAtBestBin(PrimRef* refs, const Range& r, Range* left, Range* right) {
  BinMapping<kBins> map(r.centroids);
  Bins<kBins> bins;
  if (r.size() >= kParallelBinning) {
    std::mutex mutex;
    parallelForChunks(int64_t(r.size()), kParallelBinning / 4, [&](int64_t b, int64_t e) {
      auto local = std::make_unique<Bins<kBins>>();
      local->add(refs, r.begin + uint32_t(b), r.begin + uint32_t(e), map);
      std::lock_guard<std::mutex> lock(mutex);
      bins.merge(*local);
    });
  } else {
    bins.add(refs, r.begin, r.end, map);
  }
  // SAH cost of splitting before bin i: area-weighted counts of the two sides.
  int bestAxis = -1, bestBin = 0;
  float bestCost = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (map.scale[a] == 0.0f) continue;
    float rightArea[kBins];
    uint32_t rightCount[kBins];
    Box3 acc;
    uint32_t n = 0;
    for (int i = kBins - 1; i > 0; --i) {
      acc.grow(bins.box[a][i]);
      n += bins.count[a][i];
      rightArea[i] = acc.halfArea();
      rightCount[i] = n;
    }
    acc = Box3();
    n = 0;
    for (int i = 1; i < kBins; ++i) {
      acc.grow(bins.box[a][i - 1]);
      n += bins.count[a][i - 1];
      if (n == 0 || rightCount[i] == 0) continue;
      float cost = acc.halfArea() * float(n) + rightArea[i] * float(rightCount[i]);
      if (cost < bestCost) bestCost = cost, bestAxis = a, bestBin = i;
    }
  }
  if (bestAxis < 0) return false;

  // The same mapping as the binning, so the sides match the bins' bounds exactly.
  PrimRef* mid = std::partition(refs + r.begin, refs + r.end, [&](const PrimRef& p) {
    int b[4];
    map.bins(p, b);
    return b[bestAxis] < bestBin;
  });
  left->begin = r.begin, right->end = r.end;
  left->end = right->begin = uint32_t(mid - refs);
  left->bounds = left->centroids = right->bounds = right->centroids = Box3();
  for (int b = 0; b < kBins; ++b) {
    Range* side = b < bestBin ? left : right;
    side->bounds.grow(bins.box[bestAxis][b]);
    side->centroids.grow(bins.centroids[bestAxis][b]);
  }
  return true;
}

// Splits r into two non-empty parts: at the lowest-SAH bin boundary (fewer bins for
// small ranges, where building the bins would dominate), or (when `median`, or when
// every centre coincides) at the median along the widest axis of the centres.
void splitRange(PrimRef* refs, const Range& r, bool median, Range* left, Range* right) {
  if (!median) {
    bool split = r.size() <= 64 ? splitAtBestBin<8>(refs, r, left, right)
                                : splitAtBestBin<kMaxBins>(refs, r, left, right);
    if (split) return;
  }
  left->begin = r.begin, right->end = r.end;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (r.centroids.upper[a] - r.centroids.lower[a] > r.centroids.upper[axis] - r.centroids.lower[axis]) axis = a;
  uint32_t mid = r.begin + r.size() / 2;
  std::nth_element(refs + r.begin, refs + mid, refs + r.end,
                   [axis](const PrimRef& p, const PrimRef& q) { return p.centroid(axis) < q.centroid(axis); });
  left->end = right->begin = mid;
  computeRangeBounds(refs, left);
  computeRangeBounds(refs, right);
}

void setChildBox(Bvh8Node* node, int slot, const Box3& box) {
  for (int a = 0; a < 3; ++a) {
    node->bounds[2 * a][slot] = box.lower[a];
    node->bounds[2 * a + 1][slot] = box.upper[a];
  }
}

void initNode(Bvh8Node* node) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (int s = 0; s < kBvhWidth; ++s) {
    for (int a = 0; a < 3; ++a) {
      node->bounds[2 * a][s] = kInf;
      node->bounds[2 * a + 1][s] = -kInf;
    }
    node->child[s] = Bvh8Node::kNoChild;
  }
}

// Appends `part` to `out`, shifting its local node and leaf indices; returns the code of
// part's root node in out.
int32_t appendSubtree(Subtree&& part, Subtree* out) {
  int32_t nodeOffset = int32_t(out->nodes.size());
  uint32_t leafOffset = uint32_t(out->leaves.size());
  for (Bvh8Node& node : part.nodes) {
    for (int32_t& c : node.child) {
      if (c == Bvh8Node::kNoChild) continue;
      c = Bvh8Node::isLeaf(c) ? leafRef(leafIndex(c) + leafOffset) : c + nodeOffset;
    }
  }
  out->nodes.insert(out->nodes.end(), part.nodes.begin(), part.nodes.end());
  out->leaves.insert(out->leaves.end(), part.leaves.begin(), part.leaves.end());
  out->depth = std::max(out->depth, part.depth);
  return nodeOffset;
}

// Builds the subtree over r (more than kMaxLeafSize primitives) at wide level `level`
// into `out`, appending its root node first; returns the root's index in out.
int32_t buildNode(PrimRef* refs, const Range& r, int level, Subtree* out) {
  // Form up to 8 children by repeatedly splitting the child with the largest surface.
  Range children[kBvhWidth];
  int count = 1;
  children[0] = r;
  bool median = level >= kSahDepth;
  while (count < kBvhWidth) {
    int pick = -1;
    float largest = -1.0f;
    for (int i = 0; i < count; ++i) {
      if (children[i].size() <= kMaxLeafSize) continue;
      float area = children[i].bounds.halfArea();
      if (area > largest) largest = area, pick = i;
    }
    if (pick < 0) break;
    Range a, b;
    splitRange(refs, children[pick], median, &a, &b);
    children[pick] = a;
    children[count++] = b;
  }

  int32_t index = int32_t(out->nodes.size());
  out->nodes.emplace_back();
  initNode(&out->nodes[index]);
  out->depth = std::max(out->depth, level + 1);
  for (int i = 0; i < count; ++i) setChildBox(&out->nodes[index], i, children[i].bounds);

  // Leaves first (they only record their range), then the inner children.
  int inner[kBvhWidth];
  int innerCount = 0;
  for (int i = 0; i < count; ++i) {
    if (children[i].size() <= kMaxLeafSize) {
      out->nodes[index].child[i] = leafRef(uint32_t(out->leaves.size()));
      out->leaves.push_back({children[i].begin, children[i].end});
    } else {
      inner[innerCount++] = i;
    }
  }
  if (r.size() >= kParallelSubtrees && innerCount > 1) {
    Subtree parts[kBvhWidth];
    parallelFor(innerCount, 1, [&](int64_t k) { buildNode(refs, children[inner[k]], level + 1, &parts[k]); });
    for (int k = 0; k < innerCount; ++k) out->nodes[index].child[inner[k]] = appendSubtree(std::move(parts[k]), out);
  } else {
    for (int k = 0; k < innerCount; ++k) {
      int32_t code = buildNode(refs, children[inner[k]], level + 1, out);
      out->nodes[index].child[inner[k]] = code;
    }
  }
  return index;
}

}  // namespace

void buildBvh8(const GaussianScene& scene, const TraceSettings& settings, Bvh8BuildResult* out) {
  *out = Bvh8BuildResult();
  size_t n = scene.size();

  // Kernel data and proxy box of every Gaussian; those without a proxy are left out.
  std::vector<GaussianLane> lanes(n);
  std::vector<PrimRef> refs(n);
  std::vector<uint8_t> valid(n);
  parallelFor(int64_t(n), 4096, [&](int64_t i) {
    valid[i] = computeGaussianLane(scene, size_t(i), settings, &lanes[i], &refs[i].box);
    refs[i].setId(uint32_t(i));
  });
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    if (valid[i])
      refs[kept++] = refs[i];
    else
      out->leftOut.push_back(uint32_t(i));
  }
  refs.resize(kept);
  out->stats.gaussians = refs.size();
  if (refs.empty()) return;

  // The root is always an inner node, so traversal starts the same way for every scene.
  Range root;
  root.begin = 0;
  root.end = uint32_t(refs.size());
  computeRangeBounds(refs.data(), &root);
  Subtree tree;
  if (root.size() <= kMaxLeafSize) {
    tree.nodes.emplace_back();
    initNode(&tree.nodes[0]);
    setChildBox(&tree.nodes[0], 0, root.bounds);
    tree.nodes[0].child[0] = leafRef(0);
    tree.leaves.push_back({root.begin, root.end});
    tree.depth = 1;
  } else {
    buildNode(refs.data(), root, 0, &tree);
  }

  // Leaves: blocks of 8 lanes, consecutive per leaf; each child code gets its blocks.
  std::vector<uint32_t> firstBlock(tree.leaves.size() + 1, 0);
  for (size_t l = 0; l < tree.leaves.size(); ++l)
    firstBlock[l + 1] = firstBlock[l] + (tree.leaves[l].end - tree.leaves[l].begin + kBvhWidth - 1) / kBvhWidth;
  GLINT_CHECK(firstBlock.back() < (1u << 28), "too many leaf blocks for the BVH's child codes");
  for (Bvh8Node& node : tree.nodes) {
    for (int32_t& c : node.child) {
      if (c == Bvh8Node::kNoChild || !Bvh8Node::isLeaf(c)) continue;
      uint32_t l = leafIndex(c);
      c = Bvh8Node::leafCode(firstBlock[l], int(firstBlock[l + 1] - firstBlock[l]));
    }
  }
  out->blocks.resize(firstBlock.back());
  parallelFor(int64_t(tree.leaves.size()), 256, [&](int64_t l) {
    const LeafRange& range = tree.leaves[l];
    for (uint32_t b = firstBlock[l]; b < firstBlock[l + 1]; ++b) {
      Bvh8Block& block = out->blocks[b];
      for (int lane = 0; lane < kBvhWidth; ++lane) {
        uint32_t i = range.begin + (b - firstBlock[l]) * kBvhWidth + uint32_t(lane);
        if (i < range.end)
          block.setLane(lane, lanes[refs[i].id()], refs[i].id());
        else
          block.disableLane(lane);
      }
    }
  });
  out->nodes = std::move(tree.nodes);
  out->stats.nodes = out->nodes.size();
  out->stats.leaves = tree.leaves.size();
  out->stats.blocks = out->blocks.size();
  out->stats.depth = tree.depth;
}

}  // namespace glint
