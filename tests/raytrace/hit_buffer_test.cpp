// The fast tracer's hit buffer: pops in exact (key, id) order under random pushes, pops,
// ties and shrinks, against a sorted reference.
#include "raytrace/fast/hit_buffer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "math/rng.h"

namespace glint {
namespace {

template <typename Hit>
Hit hitAt(float key, uint32_t id) {
  Hit h{};
  h.id = id;
  h.key = key;
  h.alpha = float(id) * 0.25f;  // a payload to check it travels with its hit
  return h;
}

template <typename Hit>
void expectOrderUnderRandomUse() {
  Rng rng(17);
  HitBuffer<256, Hit> buffer(64);
  std::vector<HitOrder> reference;
  uint32_t nextId = 0;
  for (int step = 0; step < 20000; ++step) {
    float u = rng.uniform();
    if (u < 0.55f && !buffer.full()) {
      // Few distinct keys, so ties (broken by id) are common.
      float key = float(int(rng.uniform() * 40.0f)) * 0.125f - 1.0f;
      uint32_t id = (nextId++ * 2654435761u) % 1000u;
      buffer.push(hitAt<Hit>(key, id));
      reference.push_back({key, id});
    } else if (u < 0.97f && !buffer.empty()) {
      auto nearest = std::min_element(reference.begin(), reference.end());
      Hit h = buffer.popNearest();
      ASSERT_EQ(h.key, nearest->key);
      ASSERT_EQ(h.id, nearest->id);
      ASSERT_EQ(h.alpha, float(h.id) * 0.25f);
      reference.erase(nearest);
    } else if (buffer.size() >= 4) {
      int keep = buffer.size() / 2;
      std::sort(reference.begin(), reference.end());
      HitOrder cut = buffer.shrink(keep);
      ASSERT_EQ(cut.key, reference[size_t(keep)].key);
      ASSERT_EQ(cut.id, reference[size_t(keep)].id);
      reference.resize(size_t(keep));
    }
    ASSERT_EQ(buffer.size(), int(reference.size()));
  }
}

TEST(HitBuffer, PopsInKeyThenIdOrderUnderRandomUse) {
  expectOrderUnderRandomUse<KeyedHit>();
}

}  // namespace
}  // namespace glint
