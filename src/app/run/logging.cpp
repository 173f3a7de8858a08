// Logging set-up: see logging.hpp.
#include "app/run/logging.hpp"

#include <spdlog/sinks/ansicolor_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace app {

namespace {
int g_rank = 0;
constexpr const char* kFilePattern = "[%Y-%m-%d %H:%M:%S] %l: %v";
// Rank 0's lines before the log file exists (set-up, preparation): copied into it when it opens.
std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> g_early;
std::shared_ptr<spdlog::sinks::basic_file_sink_mt> g_file;  // the run's log.txt (rank 0)
}  // namespace

void setup_logging(int rank, int verbosity) {
  g_rank = rank;
  spdlog::sink_ptr sink;
  if (isatty(STDERR_FILENO) != 0) {
    sink = std::make_shared<spdlog::sinks::ansicolor_stderr_sink_mt>();
  } else {
    sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  }
  auto logger = std::make_shared<spdlog::logger>("mpmxdem", sink);
  if (rank == 0) {
    logger->set_pattern("[%H:%M:%S] %^%l%$: %v");
    logger->set_level(verbosity >= 2   ? spdlog::level::trace
                      : verbosity == 1 ? spdlog::level::debug
                                       : spdlog::level::info);
  } else {
    logger->set_pattern("[%H:%M:%S] rank " + std::to_string(rank) + " %^%l%$: %v");
    logger->set_level(verbosity >= 2 ? spdlog::level::debug : spdlog::level::warn);
  }
  if (rank == 0) {
    g_early = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(4096);
    g_early->set_pattern(kFilePattern);
    logger->sinks().push_back(g_early);
  }
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

void add_log_file(const std::string& path) {
  if (g_rank != 0) return;
  auto& sinks = spdlog::default_logger()->sinks();
  if (g_early) {
    std::string early;
    for (const auto& line : g_early->last_formatted()) early += line;
    if (std::FILE* f = std::fopen(path.c_str(), "a"); f != nullptr) {
      std::fputs(early.c_str(), f);
      std::fclose(f);
    }
    sinks.erase(std::remove(sinks.begin(), sinks.end(), g_early), sinks.end());
    g_early.reset();
  }
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path, false);
  file->set_pattern(kFilePattern);
  sinks.push_back(file);
  g_file = file;
}

void remove_log_file() noexcept {
  try {
    if (!g_file) return;
    g_file->flush();
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), g_file), sinks.end());
    g_file.reset();  // closes the file
  } catch (...) {
  }
}

}  // namespace app
