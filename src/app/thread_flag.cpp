// The shared --threads flag; the limit itself is core/parallel.h's ThreadLimit.
#include "app/thread_flag.h"

#include "train/train_config.h"

namespace glint {

CLI::Option* addThreadsFlag(CLI::App* cmd, int* threads, const std::string& more) {
  return cmd
      ->add_option("--threads", *threads,
                   "Worker threads, " + std::to_string(kThreadsRange.min) + " to " + std::to_string(kThreadsRange.max) +
                       " (0 = all cores)" + (more.empty() ? "" : "; " + more))
      ->check(CLI::Range(kThreadsRange.min, kThreadsRange.max))
      ->capture_default_str();
}

}  // namespace glint
