// The training step. Determinism: a step's rays depend only on (seed, step); each path's
// result depends on its keys alone, whichever wavefront traces it; the batch (each rank's
// share of it in an MPI job) is cut into one contiguous lane per slot (one slot per thread),
// each slot accumulates its lane in ray order into its own gradient buffer, and the buffers
// are summed in slot order, then over the ranks in rank order. So a run is reproducible bit
// for bit for a given seed, rank count and thread count, resumed or not, and N ranks of one
// thread each give the bits of one process of N threads. With the GPU's backward batch
// (sorted sums, raytrace/backward_batch.h) each wavefront's jobs go in the same lane order
// and each Gaussian's hits are summed in that order, so a GPU run is reproducible too, for
// a given seed, thread count and wavefront size; its bits are not the CPU's.
#include "train/trainer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

#include "core/cluster.h"
#include "core/error.h"
#include "core/parallel.h"
#include "train/densify.h"
#include "train/far_field.h"
#include "train/rank_sync.h"
#include "train/reflection_seeds.h"
#include "train/roughness_shift.h"

namespace glint {

struct Trainer::Slot {
  GaussianGradients gradient;
  std::vector<float> splitScore;  // densification score of this slot's hits
  RayBackwardScratch<float> scratch;
  LossTerms terms;
  int64_t hitCount = 0;
  int64_t overflowed = 0;
  int64_t reflected = 0;
  ResidualHistogram roughnessResiduals;  // prior - model roughness (StepReport::roughnessOffset)
  // With a BackwardBatch: this slot's backward jobs of the current wavefront, and their hits.
  std::vector<BackwardJob> jobs;
  std::vector<HitRecord> jobHits;
};

namespace {
CullRegion cullRegion(const PruneSettings& p) {
  return p.cameraCullRegion;
}
}  // namespace

Trainer::Trainer(const TrainConfig& config, const TrainingViews& views, std::vector<CameraSphere> spheres,
                 GaussianScene initial, float sceneExtent, const std::string& tracerKind)
    : config_(config), views_(views), spheres_(std::move(spheres)), scene_(std::move(initial)),
      extent_(sceneExtent), adam_(config.adam) {
  scene_.filter(outsideCameraSpheres(scene_, spheres_, cullRegion(config_.prune)));
  if (scene_.empty()) throw Error(config_.dataset, "the initial scene has no Gaussians outside the camera spheres");
  adam_.reset(scene_.size());
  pruneWeight_.assign(scene_.size(), 0.0f);
  densifyScore_.assign(scene_.size(), 0.0f);
  setUp(tracerKind);
}

Trainer::Trainer(const TrainConfig& config, const TrainingViews& views, std::vector<CameraSphere> spheres,
                 TrainingState state, const std::string& tracerKind)
    : config_(config), views_(views), spheres_(std::move(spheres)), scene_(std::move(state.scene)),
      extent_(state.sceneExtent), step_(state.step), adam_(config.adam),
      pruneWeight_(std::move(state.pruneWeight)), densifyScore_(std::move(state.densifyScore)),
      roughnessShift_(state.roughnessShift) {
  adam_.reset(scene_.size());
  adam_.firstMoment() = std::move(state.adam.firstMoment());
  adam_.secondMoment() = std::move(state.adam.secondMoment());
  adam_.setStepCount(state.adam.stepCount());
  setUp(tracerKind);
}

Trainer::~Trainer() = default;

void Trainer::setUp(const std::string& tracerKind) {
  tracer_ = makeGaussianTracer(tracerKind);
  tracer_->build(scene_, config_.trace);
  backwardBatch_ = makeBackwardBatch(tracerKind);  // the GPU's for a GPU tracer, else none
  int slots = std::max(1, maxThreads());
  for (int s = 0; s < slots; ++s) slots_.push_back(std::make_unique<Slot>());
}

TrainingState Trainer::state() const {
  TrainingState s;
  s.step = step_;
  s.sceneExtent = extent_;
  s.scene = scene_;
  s.adam = adam_;
  s.pruneWeight = pruneWeight_;
  s.roughnessShift = roughnessShift_;
  s.densifyScore = densifyScore_;
  s.configJson = toJson(config_).dump();
  return s;
}

void Trainer::forwardBackward(std::span<const BatchRay> batch, bool backward, StepReport* report) {
  LossNormalisation norm;
  norm.diffuseRays = double(batch.size());
  int64_t surface = 0;
  for (const BatchRay& b : batch) surface += views_.surfaceAt(b.view, b.pixel) ? 1 : 0;
  norm.surfaceRays = double(std::max<int64_t>(surface, 1));

  const size_t n = scene_.size();
  const int64_t slotCount = int64_t(slots_.size());
  const int64_t rays = int64_t(batch.size());
  const bool reflections = config_.bounces > 0 && step_ >= config_.reflectionWarmup;
  PathSettings pathSettings = config_.path();
  if (!reflections) pathSettings.bounces = 0;
  pathSettings.hitListCapacity = hitCapacityWithoutOverflow(config_.trace);
  // Camera rays one by one: bundles of random pixels were slower (train_bench), and those of
  // whole images no faster in training mode, with its exact tail and hit lists (train_bench,
  // 2 threads: 0.092 against 0.090 Mrays/s, within the runs' variation).
  pathSettings.primaryCoherence = RayCoherence::Scattered;
  PathGradientSettings gradients;
  gradients.roughnessFromSpecular = config_.loss.roughnessFromSpecular;
  // With the tint option L_r's F0 gradient is there to learn the tint a metalness prior
  // lacks; an F0 prior has its tint already, and L_r's noisy light only disturbs it
  // (builtin:spheres' network kind: -0.42 dB of specular, docs/captures.md).
  const bool tintToLearn = !config_.f0TintFromReflections || views_.supervised().f0BrightnessOnly;
  gradients.f0FromSpecular = tintToLearn ? config_.loss.f0FromSpecular : 0.0f;
  gradients.f0FromSpecularMetalsOnly = config_.f0TintFromReflections;  // the tint is a metal's
  gradients.path = pathSettings;
  const bool scoring = backward && scoringSplits();
  const bool shiftInvariant = config_.roughnessShiftInvariant;
  if (scoring) {
    sigmaMax_.resize(n);
    parallelForChunks(int64_t(n), 8192, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) {
        const Vec3f& s = scene_.logScale[size_t(i)];
        sigmaMax_[size_t(i)] = std::exp(std::max({s.x, s.y, s.z}));
      }
    });
  }
  // With a BackwardBatch the slots hand it their jobs, and it sums the gradients.
  BackwardBatch* const device = backward ? backwardBatch_.get() : nullptr;
  if (device) device->begin(scene_, config_.trace, scoring ? std::span<const float>(sigmaMax_) : std::span<const float>());
  // Slots start empty; each accumulates its lane (below) of the batch.
  parallelFor(slotCount, 1, [&](int64_t s) {
    Slot& slot = *slots_[s];
    if (!device) {
      if (slot.gradient.size() != n)
        slot.gradient.reset(n);
      else
        slot.gradient.zero(0, n);
      if (scoring) slot.splitScore.assign(n, 0.0f);
    }
    slot.terms = {};
    slot.hitCount = slot.overflowed = slot.reflected = 0;
    slot.roughnessResiduals.clear();
  });
  // This process's share of the batch (all of it unless an MPI job splits it over ranks),
  // cut into one contiguous lane per slot. Each slot adds its lane's rays in ray order, and
  // the lanes are summed in slot order and then in rank order, so N ranks of one thread give
  // the same bits as one process of N threads.
  const cluster::Share share = cluster::myShare(rays);
  std::vector<cluster::Share> lanes(static_cast<size_t>(slotCount));
  int64_t longestLane = 0;
  for (int64_t s = 0; s < slotCount; ++s) {
    cluster::Share lane = cluster::shareOf(share.end - share.begin, int(s), int(slotCount));
    lanes[size_t(s)] = {share.begin + lane.begin, share.begin + lane.end};
    longestLane = std::max(longestLane, lane.end - lane.begin);
  }
  // The lanes go in wavefronts of at most wavefrontRays_ paths, an equal part of each lane
  // per wavefront: each is traced with every segment recorded (hits included), then its
  // losses and backward pass run, each slot on its lane's part. The records' memory (about
  // 6 KB per path) stays bounded whatever the batch size. The sample key is the step, so
  // each step draws new reflection directions.
  const int64_t perLane = std::max<int64_t>(1, wavefrontRays_ / slotCount);
  std::vector<int64_t> laneStart(static_cast<size_t>(slotCount) + 1);
  for (int64_t offset = 0; offset < longestLane; offset += perLane) {
    int64_t count = 0;
    for (int64_t s = 0; s < slotCount; ++s) {
      laneStart[size_t(s)] = count;
      const cluster::Share& lane = lanes[size_t(s)];
      count += std::clamp<int64_t>(lane.end - lane.begin - offset, 0, perLane);
    }
    laneStart[size_t(slotCount)] = count;
    // The batch ray of wavefront entry r of slot s.
    auto batchRay = [&](int64_t s, int64_t r) -> const BatchRay& {
      return batch[size_t(lanes[size_t(s)].begin + offset + r - laneStart[size_t(s)])];
    };
    rays_.resize(size_t(count));
    keys_.resize(size_t(count));
    paths_.resize(size_t(count));
    for (int64_t s = 0; s < slotCount; ++s)
      for (int64_t r = laneStart[size_t(s)]; r < laneStart[size_t(s) + 1]; ++r) {
        const BatchRay& b = batchRay(s, r);
        rays_[size_t(r)] = b.ray;
        keys_[size_t(r)] = {b.view, b.pixel, uint64_t(step_)};
      }
    auto traceStart = std::chrono::steady_clock::now();
    pathBatch_.trace(*tracer_, rays_, keys_, config_.seed, pathSettings, paths_, /*record=*/true);
    auto backwardStart = std::chrono::steady_clock::now();
    report->traceSeconds += std::chrono::duration<double>(backwardStart - traceStart).count();
    parallelFor(slotCount, 1, [&](int64_t s) {
      Slot& slot = *slots_[s];
      slot.jobs.clear();
      slot.jobHits.clear();
      auto sink = [&](uint32_t id, const HitGradient<float>& g) {
        slot.gradient.add(id, g);
        if (scoring) slot.splitScore[id] += splitScore(g, sigmaMax_[id]);
      };
      for (int64_t r = laneStart[size_t(s)]; r < laneStart[size_t(s) + 1]; ++r) {
        const BatchRay& b = batchRay(s, r);
        PixelTarget target = views_.target(b.view, b.pixel);
        std::span<const PathSegment> path = pathBatch_.path(size_t(r));
        const RayResult& result = path[0].result;
        if (target.surface && target.hasDepth && !withinDepthBand(result.depth, target.depth, config_.loss.depthBand))
          target.hasDepth = false;  // a prior that disagrees with the geometry does not pull it
        if (target.surface && target.hasRoughness) {
          slot.roughnessResiduals.add(double(target.roughness) - double(result.roughness));
          // The shift-invariant term compares r + b with the prior p, b the last step's offset.
          if (shiftInvariant) target.roughness -= roughnessShift_;
        }
        const Rgb specular = reflections ? paths_[size_t(r)].specular : Rgb(0.0f);
        slot.terms += rayLoss(result, target, norm, specular, config_.loss.normalHuber);
        slot.hitCount += int64_t(path[0].hits.hits.size());
        Rgb v_specular(0.0f), v_photograph(0.0f);
        if (reflections) {
          slot.reflected += int64_t(path.size()) - 1;
          if (target.hasSpecular) {
            slot.terms.specular += specularLoss(specular, target, norm);
            v_specular = specularLoss_vjp(specular, target, norm, config_.loss);
          }
          // Before reflections train the sum would be the diffuse alone, and the photograph's
          // highlights would be baked into it.
          if (target.hasPhotograph) {
            slot.terms.photograph += photographLoss(result.diffuse + specular, target, norm);
            v_photograph = photographLoss_vjp(result.diffuse + specular, target, norm, config_.loss);
          }
        }
        if (!backward) continue;
        RayResultAdjoint v_first = rayLoss_vjp(result, target, norm, config_.loss, specular);
        // Fitting diffuse + specular to the final image sends the colour's gradient down the path too.
        if (reflections && target.finalColour) v_specular += v_first.v_diffuse;
        v_first.v_diffuse += v_photograph;
        v_specular += v_photograph;
        if (device)
          slot.overflowed += appendBackwardJobs(path, v_first, v_specular, gradients, &slot.jobs, &slot.jobHits);
        else
          slot.overflowed +=
              tracePath_vjp<float>(scene_, config_.trace, path, v_first, v_specular, gradients, slot.scratch, sink);
      }
    });
    if (device) handToDevice(device);
    report->backwardSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - backwardStart).count();
  }
  // Reduce into slot 0, in slot order for every Gaussian (or take the BackwardBatch's sums).
  auto reduceStart = std::chrono::steady_clock::now();
  GaussianGradients& total = slots_[0]->gradient;
  std::vector<float>& score = slots_[0]->splitScore;
  if (device) {
    device->finish(&total, scoring ? &score : nullptr);
  } else {
    parallelForChunks(int64_t(n), 8192, [&](int64_t begin, int64_t end) {
      for (size_t s = 1; s < slots_.size(); ++s) total.addRange(slots_[s]->gradient, size_t(begin), size_t(end));
      if (scoring)
        for (size_t s = 1; s < slots_.size(); ++s)
          for (int64_t i = begin; i < end; ++i) score[size_t(i)] += slots_[s]->splitScore[size_t(i)];
    });
  }
  const double reduceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - reduceStart).count();
  report->reduceSeconds += reduceSeconds;
  report->backwardSeconds += reduceSeconds;
  // Then over the ranks of an MPI job, in rank order.
  LossTerms terms;
  int64_t counters[3] = {0, 0, 0};
  ResidualHistogram residuals;
  for (const auto& slot : slots_) {
    residuals.merge(slot->roughnessResiduals);
    terms += slot->terms;
    counters[0] += slot->hitCount;
    counters[1] += slot->overflowed;
    counters[2] += slot->reflected;
  }
  if (cluster::distributed()) {
    // Waiting for the slowest rank is timed apart from the exchange itself.
    auto waitStart = std::chrono::steady_clock::now();
    cluster::barrier();
    report->waitSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart).count();
    const ExchangeStats exchange =
        sumOverRanks(total, scoring ? std::span<float>(score) : std::span<float>(), exchangeMode_);
    double t[7] = {terms.diffuse, terms.depth,    terms.normal,    terms.roughness,
                   terms.f0,      terms.specular, terms.photograph};
    cluster::sumInRankOrder(std::span<double>(t, 7));
    terms = {t[0], t[1], t[2], t[3], t[4], t[5], t[6]};
    cluster::sumInRankOrder(std::span<int64_t>(counters, 3));
    cluster::sumInRankOrder(residuals.counts());
    report->exchangeSeconds += exchange.seconds;
    report->exchangedBytes += exchange.bytesIn;
    report->sparseExchange = exchange.sparse;
  }
  if (scoring)
    parallelForChunks(int64_t(n), 8192, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i) densifyScore_[size_t(i)] += score[size_t(i)];
    });
  report->terms += terms;
  report->hits += counters[0];
  report->overflowedRays += counters[1];
  report->reflectedSegments += counters[2];
  report->rays += rays;
  // The batch's offset: its median residual, the b that minimises the batch's L1 roughness
  // term over b (train/roughness_shift.h). The shift-invariant term takes it out of the next
  // step's priors: it lags the model by one step, so the backward pass holds it constant.
  report->roughnessOffset = float(residuals.median());
  if (backward && shiftInvariant && residuals.count() > 0) roughnessShift_ = report->roughnessOffset;
}

void Trainer::handToDevice(BackwardBatch* device) {
  // The slots' jobs in slot order (each slot's in ray order), their hits renumbered into
  // one array: the order of the CPU's own backward pass.
  deviceJobs_.clear();
  deviceHits_.clear();
  for (const auto& slot : slots_) {
    const uint32_t offset = uint32_t(deviceHits_.size());
    for (BackwardJob job : slot->jobs) {
      job.firstHit += offset;
      deviceJobs_.push_back(job);
    }
    deviceHits_.insert(deviceHits_.end(), slot->jobHits.begin(), slot->jobHits.end());
  }
  device->add(deviceJobs_, deviceHits_);
}

void Trainer::setBackwardBatch(std::unique_ptr<BackwardBatch> batch) { backwardBatch_ = std::move(batch); }

void Trainer::setWavefrontRays(int64_t paths) {
  GLINT_CHECK(paths > 0, "Trainer::setWavefrontRays: a wavefront holds at least one path");
  wavefrontRays_ = paths;
}

const GaussianGradients& Trainer::lastGradient() const { return slots_[0]->gradient; }

const std::vector<float>& Trainer::lastSplitScores() const { return slots_[0]->splitScore; }

StepReport Trainer::step() {
  auto start = std::chrono::steady_clock::now();
  StepReport report;
  if (config_.bounces > 0 && step_ == config_.reflectionWarmup)
    std::tie(report.farFieldAdded, report.reflectionSeedsAdded) = addFarField();
  if (config_.batchImages > 0)
    views_.drawWholeImages(config_.seed, step_, config_.batchImages, &batch_);
  else
    views_.drawBatch(config_.seed, step_, config_.batchRays, config_.batchViews, &batch_);
  forwardBackward(batch_, /*backward=*/true, &report);
  const GaussianGradients& gradient = slots_[0]->gradient;
  for (size_t i = 0; i < scene_.size(); ++i) pruneWeight_[i] += gradient.weight[i];

  auto adamStart = std::chrono::steady_clock::now();
  adam_.step(&scene_, gradient, learningRatesAt(config_.lr, extent_, step_));
  // Scale decay (appendix: favour small Gaussians, which keep rays cheap) and the valid
  // ranges of the attributes.
  const float logDecay = std::log(config_.scaleDecay);
  parallelForChunks(int64_t(scene_.size()), 8192, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      scene_.logScale[i] += Vec3f(logDecay);
      Rgb& c = scene_.diffuse[i];
      c = {std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f)};
      scene_.roughness[i] = std::clamp(scene_.roughness[i], 0.0f, 1.0f);
      Rgb& f = scene_.f0[i];
      f = {std::clamp(f.x, 0.0f, 1.0f), std::clamp(f.y, 0.0f, 1.0f), std::clamp(f.z, 0.0f, 1.0f)};
    }
  });
  report.adamSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - adamStart).count();
  ++step_;
  const auto housekeepingStart = std::chrono::steady_clock::now();
  housekeeping(&report);
  report.housekeepingSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - housekeepingStart).count();
  report.step = step_;
  report.gaussians = scene_.size();
  report.loss = report.terms.weighted(config_.loss);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::pair<size_t, size_t> Trainer::addFarField() {
  // Seeds first: their reflected rays are traced through the warm-up's scene alone.
  // In an MPI job rank 0 places them and the others take its Gaussians (train/rank_sync.h).
  GaussianScene seeds, far;
  if (cluster::isRoot()) {
    seeds = reflectionSeeds(config_.farField, views_, *tracer_, config_.trace, config_.backfaceSkip, extent_,
                            config_.seed);
    if (config_.farField.count > 0 || !config_.farField.boxes.empty()) {
      Vec3d sum(0.0);
      for (size_t v = 0; v < views_.viewCount(); ++v) sum += views_.camera(v).position();
      const Vec3f centre = Vec3f(sum / double(views_.viewCount()));
      far = farFieldGaussians(config_.farField, centre, extent_, config_.seed);
      // The cloud loses all of each camera sphere: a random Gaussian behind a camera is a
      // floater in the reflections of every other view. Boxes are placed by the user, often
      // around what lies behind the cameras (builtin:room's hidden box), and keep theirs.
      std::vector<bool> keep = outsideCameraSpheres(far, spheres_, CullRegion::WholeSphere);
      std::fill(keep.begin() + config_.farField.count, keep.end(), true);
      far.filter(keep);
      carveObservedFreeSpace(&far, views_, config_.trace);
    }
  }
  broadcastScene(&seeds);
  broadcastScene(&far);
  if (far.size() == 0 && seeds.size() == 0) return {0, 0};
  for (size_t i = 0; i < far.size(); ++i) scene_.append(far, i);
  for (size_t i = 0; i < seeds.size(); ++i) scene_.append(seeds, i);
  const size_t added = far.size() + seeds.size();
  adam_.grow(scene_.size());
  pruneWeight_.resize(scene_.size(), 0.0f);
  densifyScore_.resize(scene_.size(), 0.0f);
  tracer_->build(scene_, config_.trace);
  return {added, seeds.size()};
}

double Trainer::raysPerStep() const {
  if (config_.batchImages > 0)
    return double(std::min<size_t>(size_t(config_.batchImages), views_.viewCount())) * views_.meanPixelsPerView();
  return double(config_.batchRays);
}

bool Trainer::scoringSplits() const {
  const DensifySettings& d = config_.densify;
  // The score of a densify step is what the steps since the previous one accumulated.
  return d.fraction > 0 && step_ < d.stop && step_ + d.every >= d.start;
}

void Trainer::housekeeping(StepReport* report) {
  bool changed = false;
  const PruneSettings& p = config_.prune;
  if (step_ % p.every == 0) {
    if (step_ < p.start) {  // intervals before the first prune only restart the accumulator
      std::fill(pruneWeight_.begin(), pruneWeight_.end(), 0.0f);
    } else {
      report->pruned = prune();
      changed = report->pruned > 0;
    }
  }
  const DensifySettings& d = config_.densify;
  if (d.fraction > 0 && step_ % d.every == 0) {
    if (step_ >= d.start && step_ <= d.stop) report->split = densify();
    changed = changed || report->split > 0;
    std::fill(densifyScore_.begin(), densifyScore_.end(), 0.0f);
  }
  if (changed)
    tracer_->build(scene_, config_.trace);
  else
    tracer_->refit();
}

size_t Trainer::prune() {
  const PruneSettings& p = config_.prune;
  // Weight per full training image, averaged over the interval's steps (appendix A.4).
  const double perImage = views_.meanPixelsPerView() / raysPerStep();
  const double scale = perImage / double(p.every);
  // The paper's threshold is for its resolution; at fewer pixels a Gaussian of the same
  // size collects proportionally less weight (train_config.h).
  const double threshold = p.thresholdPixels > 0
                               ? double(p.weightThreshold) * views_.meanPixelsPerView() / p.thresholdPixels
                               : double(p.weightThreshold);
  std::vector<bool> keep = outsideCameraSpheres(scene_, spheres_, cullRegion(config_.prune));
  for (size_t i = 0; i < scene_.size(); ++i)
    if (double(pruneWeight_[i]) * scale < threshold) keep[i] = false;
  broadcastMask(&keep);  // rank 0's choice in an MPI job
  size_t kept = size_t(std::count(keep.begin(), keep.end(), true));
  if (kept == 0) throw Error(config_.dataset, "pruning would remove every Gaussian at step " + std::to_string(step_) +
                                                  "; lower prune.weight_threshold");
  size_t removed = scene_.size() - kept;
  std::fill(pruneWeight_.begin(), pruneWeight_.end(), 0.0f);
  if (removed == 0) return 0;
  scene_.filter(keep);
  adam_.filter(keep);
  keepSelected(densifyScore_, keep);
  pruneWeight_.assign(scene_.size(), 0.0f);
  return removed;
}

size_t Trainer::densify() {
  const DensifySettings& d = config_.densify;
  const size_t room = size_t(std::max<int64_t>(d.maxGaussians - int64_t(scene_.size()), 0));
  std::vector<uint32_t> parents = chooseSplits(densifyScore_, d.fraction, room);
  cluster::broadcastVector(&parents);  // rank 0's choice in an MPI job
  if (parents.empty()) return 0;
  splitGaussians(&scene_, parents);
  adam_.appendCopies(parents);
  // The children share the parent's weight so far, so that the current pruning interval
  // judges them as it judges the Gaussians that were not split.
  for (uint32_t i : parents) pruneWeight_.push_back(pruneWeight_[i]);
  densifyScore_.resize(scene_.size(), 0.0f);
  return parents.size();
}

}  // namespace glint
