// Logging set-up: see logging.hpp.
#include "app/logging.hpp"

#include <spdlog/sinks/ansicolor_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <memory>

namespace app {

namespace {
int g_rank = 0;
}

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
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

void add_log_file(const std::string& path) {
  if (g_rank != 0) return;
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path, false);
  file->set_pattern("[%Y-%m-%d %H:%M:%S] %l: %v");
  spdlog::default_logger()->sinks().push_back(file);
}

}  // namespace app
