// Benchmark of data-parallel training over MPI: the training step and its parts (trace,
// backward, exchange, Adam, the rest) at each scene size, in 1 process of T threads and in
// R ranks of T/R threads started by mpirun on this machine, with the dense and the sparse
// exchange; then a model, from those measurements and stated network figures, of the
// speed-up on 4, 16 and 64 nodes and of the batch below which the exchange outlasts the
// tracing. Prints tables and writes JSON (--json FILE). Started without mpirun it measures
// the 1-process steps, then runs itself under `mpirun -np R` for the rest.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/cluster.h"
#include "core/parallel.h"
#include "scene/dataset.h"
#include "train/camera_culling.h"
#include "train/dense_init.h"
#include "train/densify.h"
#include "train/gradient_exchange.h"
#include "train/scene_extent.h"
#include "train/trainer.h"
#include "training_dataset.h"

using namespace glint;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Options {
  std::string dataset, jsonPath;
  std::vector<int> sizes = {100000, 500000};
  int steps = 4, warmup = 2, batchRays = 16384, threads = 2, ranks = 2;
  bool worker = false;
};

// A scene of exactly n Gaussians on the dataset's surfaces: the dense initialisation, every
// Gaussian split in two until there are n or more, then n of them evenly spaced in index
// order (which is spatial order within the initialisation and within the split children, so
// the subset covers every surface).
GaussianScene sceneOf(const Dataset& dataset, size_t n) {
  GaussianScene scene = denseInitialisation(dataset).scene;
  while (scene.size() < n) {
    std::vector<uint32_t> all(scene.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
    splitGaussians(&scene, all);
  }
  const size_t m = scene.size();
  std::vector<bool> keep(m, false);
  for (size_t i = 0; i < m; ++i) keep[i] = (i + 1) * n / m > i * n / m;
  scene.filter(keep);
  return scene;
}

// Mean parts of `steps` training steps after `warmup` ones, on a scene of n Gaussians with
// reflections traced from the first step (2 bounces), no far field, pruning or splits (the
// count stays n).
json measure(const Options& o, const Dataset& dataset, const TrainingViews& views, size_t n, ExchangeMode mode) {
  TrainConfig config;
  config.dataset = o.dataset;
  config.batchRays = o.batchRays;
  config.reflectionWarmup = 0;
  config.farField.count = 0;
  config.farField.reflectionSeeds = 0;
  config.prune.start = config.prune.every = 1 << 30;
  config.densify.fraction = 0;
  Trainer trainer(config, views, cameraSpheres(dataset, dataset.train()), sceneOf(dataset, n),
                  sceneExtent(dataset.train()));
  trainer.setExchangeMode(mode);
  for (int i = 0; i < o.warmup; ++i) trainer.step();
  StepReport sum;
  for (int i = 0; i < o.steps; ++i) {
    StepReport r = trainer.step();
    sum.addTimes(r);
    sum.exchangedBytes += r.exchangedBytes;
    sum.hits += r.hits;
    sum.rays += r.rays;
    sum.sparseExchange = r.sparseExchange;
  }
  const double k = 1.0 / o.steps;
  json j = {{"gaussians", trainer.scene().size()},
            {"ranks", cluster::size()},
            {"threads_per_rank", maxThreads()},
            {"exchange", cluster::distributed() ? (sum.sparseExchange ? "sparse" : "dense") : "none"},
            {"step_s", sum.seconds * k},
            {"trace_s", sum.traceSeconds * k},
            {"backward_s", sum.backwardSeconds * k},
            {"wait_s", sum.waitSeconds * k},
            {"exchange_s", sum.exchangeSeconds * k},
            {"adam_s", sum.adamSeconds * k},
            {"bytes_in", double(sum.exchangedBytes) * k},
            {"hits_per_ray", double(sum.hits) / double(std::max<int64_t>(sum.rays, 1))}};
  j["other_s"] = j["step_s"].get<double>() - j["trace_s"].get<double>() - j["backward_s"].get<double>() -
                 j["wait_s"].get<double>() - j["exchange_s"].get<double>() - j["adam_s"].get<double>();
  return j;
}

// The touched Gaussians per rank of the sparse exchange, from its bytes: each rank receives
// the rows of the N - 1 others.
double touchedPerRank(const json& sparse, int width) {
  const int N = sparse["ranks"].get<int>();
  return sparse["bytes_in"].get<double>() / double(N - 1) / (4.0 + 4.0 * width);
}

struct Network {
  const char* name;
  double bitsPerSecond, latency;
};

// The exchange of one step on N nodes: every one of the C arrays is summed by an
// all-to-all and an all-gather, N - 1 message rounds each, moving 2 (N - 1) / N of the
// array per rank (dense); or every rank receives the touched rows of the N - 1 others in
// one all-gather (sparse).
double denseSeconds(double n, int width, int columns, int N, const Network& net) {
  return columns * 2.0 * (N - 1) * net.latency + 2.0 * (N - 1) / N * n * width * 4.0 * 8.0 / net.bitsPerSecond;
}
double sparseSeconds(double touched, int width, int N, const Network& net) {
  return 2.0 * (N - 1) * net.latency + (N - 1) * touched * (4.0 + 4.0 * width) * 8.0 / net.bitsPerSecond;
}

int runWorker(const Options& o) {
  Dataset dataset = Dataset::open(o.dataset);
  TrainingViews views = TrainingViews::load(dataset, dataset.train());
  json results = json::array();
  for (int n : o.sizes)
    for (ExchangeMode mode : {ExchangeMode::Dense, ExchangeMode::Sparse}) {
      json j = measure(o, dataset, views, size_t(n), mode);
      if (cluster::isRoot())
        std::fprintf(stderr, "  %d ranks, %d Gaussians, %s exchange: %.3f s per step\n", cluster::size(), n,
                     j["exchange"].get<std::string>().c_str(), j["step_s"].get<double>());
      results.push_back(j);
    }
  if (cluster::isRoot()) std::ofstream(o.jsonPath) << results.dump(1);
  return 0;
}

std::string selfPath() {
  std::error_code error;
  fs::path p = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("cluster_bench") : p.string();
}

}  // namespace

int main(int argc, char** argv) {
  cluster::join(&argc, &argv);
  CLI::App app{"Data-parallel training over MPI: step parts for 1 process and R ranks, and a cluster model"};
  Options o;
  app.add_option("--dataset", o.dataset, "Dataset (default: builtin:spheres, 40 views of 160x120, rendered into a "
                                         "temporary folder)");
  app.add_option("--gaussians", o.sizes, "Scene sizes measured")->capture_default_str();
  app.add_option("--steps", o.steps, "Steps measured per configuration")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--warmup", o.warmup, "Steps before measuring")->check(CLI::Range(0, 1000))->capture_default_str();
  app.add_option("--batch-rays", o.batchRays, "Rays per step")->check(CLI::Range(1, 1 << 24))->capture_default_str();
  app.add_option("--threads", o.threads, "Threads of the 1-process run; each of the R ranks gets threads / R")
      ->check(CLI::Range(1, 1024))->capture_default_str();
  app.add_option("--ranks", o.ranks, "Ranks of the MPI run (mpirun --oversubscribe on this machine)")
      ->check(CLI::Range(2, 64))->capture_default_str();
  app.add_option("--json", o.jsonPath, "Write the results as JSON here");
  app.add_flag("--worker", o.worker, "(internal) the MPI run's side: measure and write --json");
  CLI11_PARSE(app, argc, argv);
  if (o.worker) {
    ThreadLimit limit(o.threads);
    int code = runWorker(o);
    cluster::leave();
    return code;
  }
  if (cluster::distributed()) {
    std::fprintf(stderr, "cluster_bench: start it without mpirun; it runs mpirun itself\n");
    cluster::abortJob(2);
  }
  if (!cluster::builtWithMpi()) {
    std::fprintf(stderr, "cluster_bench: this build has no MPI (install libopenmpi-dev and reconfigure)\n");
    return 2;
  }

  fs::path temp = fs::temp_directory_path() / ("glint_cluster_bench_" + std::to_string(::getpid()));
  fs::create_directories(temp);
  if (o.dataset.empty()) {
    renderTrainingBenchDataset(temp / "D");
    o.dataset = (temp / "D").string();
  }

  // 1 process of T threads.
  json single = json::array();
  {
    ThreadLimit limit(o.threads);
    Dataset dataset = Dataset::open(o.dataset);
    TrainingViews views = TrainingViews::load(dataset, dataset.train());
    for (int n : o.sizes) {
      single.push_back(measure(o, dataset, views, size_t(n), ExchangeMode::Dense));
      std::fprintf(stderr, "  1 process, %d Gaussians: %.3f s per step\n", n, single.back()["step_s"].get<double>());
    }
  }
  // R ranks of T / R threads, by mpirun.
  const fs::path workerJson = temp / "ranks.json";
  std::ostringstream command;
  command << "mpirun --oversubscribe " << (geteuid() == 0 ? "--allow-run-as-root " : "") << "-np " << o.ranks << " "
          << selfPath() << " --worker --dataset " << o.dataset << " --json " << workerJson.string()
          << " --steps " << o.steps << " --warmup " << o.warmup << " --batch-rays " << o.batchRays << " --threads "
          << std::max(1, o.threads / o.ranks) << " --gaussians";
  for (int n : o.sizes) command << " " << n;
  std::fprintf(stderr, "%s\n", command.str().c_str());
  if (std::system(command.str().c_str()) != 0) {
    std::fprintf(stderr, "cluster_bench: the MPI run failed\n");
    return 1;
  }
  json ranks = json::parse(std::ifstream(workerJson));
  fs::remove_all(temp);

  std::printf("\nTraining step, %d rays, 2 bounces, mean of %d steps after %d (seconds; bytes received per rank)\n\n",
              o.batchRays, o.steps, o.warmup);
  std::printf("| Gaussians | hits per ray | layout | exchange | step | trace | backward | wait | exchange | Adam | other | MB in | "
              "speed-up |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  auto row = [&](const json& j, double reference) {
    std::printf("| %d | %.1f | %d x %d threads | %s | %.3f | %.3f | %.3f | %.4f | %.4f | %.4f | %.4f | %.1f | %.2f |\n",
                j["gaussians"].get<int>(), j["hits_per_ray"].get<double>(), j["ranks"].get<int>(),
                j["threads_per_rank"].get<int>(), j["exchange"].get<std::string>().c_str(), j["step_s"].get<double>(),
                j["trace_s"].get<double>(), j["backward_s"].get<double>(), j["wait_s"].get<double>(),
                j["exchange_s"].get<double>(), j["adam_s"].get<double>(),
                j["other_s"].get<double>(), j["bytes_in"].get<double>() / 1e6, reference / j["step_s"].get<double>());
  };
  for (size_t s = 0; s < o.sizes.size(); ++s) {
    row(single[s], single[s]["step_s"].get<double>());
    for (const json& j : ranks)
      if (j["gaussians"].get<int>() == o.sizes[s]) row(j, single[s]["step_s"].get<double>());
  }

  // The model: nodes like this machine (its 1-process tracing and backward rate, its Adam
  // and the rest, which every rank does whole), joined by the stated networks. Each
  // exchange costs its CPU time on this machine (its 2-rank time through shared memory,
  // which moves bytes far faster than any network) plus the network's time; the sparse
  // exchange's CPU time grows with the rows every rank adds (N x the rows of one share).
  const int width = exchangeWidth(false);
  const int columns = 10;  // 8 parameters, the blend weight, and the split score on scoring steps
  const Network networks[] = {{"10 Gbit/s, 2 us", 10e9, 2e-6},
                              {"10 Gbit/s, 20 us", 10e9, 20e-6},
                              {"100 Gbit/s, 2 us", 100e9, 2e-6},
                              {"100 Gbit/s, 20 us", 100e9, 20e-6}};
  json model = json::array();
  std::printf("\nModel of N nodes like this one: step = (trace + backward) / N + Adam + other + exchange, with the\n"
              "product's dense exchange; exchange = its CPU time here + the network's. Speed-up of rays per second\n"
              "at the same batch (%d rays) and at a batch N times larger; batch* = the batch below which the\n"
              "exchange takes longer than a node's tracing and backward pass.\n\n", o.batchRays);
  std::printf("| Gaussians | network | nodes | dense exchange s | sparse exchange s | step s | speed-up | speed-up, N x batch | batch* |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (size_t s = 0; s < o.sizes.size(); ++s) {
    const json& one = single[s];
    const double n = o.sizes[s];
    const double compute = one["trace_s"].get<double>() + one["backward_s"].get<double>();
    const double fixed = one["adam_s"].get<double>() + one["other_s"].get<double>();
    const double perRay = compute / o.batchRays;
    // Touched Gaussians of a share of B / N rays: n (1 - exp(-h B / (N n))), h fitted to the
    // sparse run's count at R ranks; and each exchange's CPU time there.
    double touched = 0, denseCpu = 0, sparseCpu = 0;
    for (const json& j : ranks) {
      if (j["gaussians"].get<int>() != o.sizes[s]) continue;
      if (j["exchange"] == "sparse") {
        touched = touchedPerRank(j, width);
        sparseCpu = j["exchange_s"].get<double>();
      } else {
        denseCpu = j["exchange_s"].get<double>();
      }
    }
    const double fraction = std::min(touched / n, 0.999999);
    const double h = -std::log(1.0 - fraction) * n * o.ranks / o.batchRays;
    for (const Network& net : networks)
      for (int N : {4, 16, 64}) {
        const double share = n * (1.0 - std::exp(-h * o.batchRays / (double(N) * n)));
        const double dense = denseCpu + denseSeconds(n, width, columns, N, net);
        const double sparse =
            sparseCpu * (N * share) / (o.ranks * std::max(touched, 1.0)) + sparseSeconds(share, width, N, net);
        const double step = compute / N + fixed + dense;
        const double speedup = (compute + fixed) / step;
        const double weakSpeedup = N * (compute + fixed) / (compute + fixed + dense);
        const double batchStar = N * dense / perRay;
        std::printf("| %.0f | %s | %d | %.4f | %.4f | %.3f | %.1f | %.1f | %.0f |\n", n, net.name, N, dense, sparse, step,
                    speedup, weakSpeedup, batchStar);
        model.push_back({{"gaussians", n}, {"network", net.name}, {"nodes", N}, {"dense_exchange_s", dense},
                         {"sparse_exchange_s", sparse}, {"step_s", step}, {"speedup", speedup},
                         {"speedup_n_times_batch", weakSpeedup}, {"batch_star", batchStar}});
      }
  }
  if (!o.jsonPath.empty()) {
    json out = {{"batch_rays", o.batchRays}, {"single", single}, {"ranks", ranks}, {"model", model}};
    std::ofstream(o.jsonPath) << out.dump(2);
  }
  return 0;
}
