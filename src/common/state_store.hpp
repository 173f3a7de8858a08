// In-memory StateWriter/StateReader: used for tests, for migrating an RVE between ranks
// (serialised to one buffer) and as the staging area of a checkpoint.
#pragma once

#include <map>
#include <variant>

#include "common/state_io.hpp"

namespace common {

class StateStore final : public StateWriter, public StateReader {
 public:
  using Field = std::variant<std::vector<double>, std::vector<std::int64_t>>;

  void write(std::string_view name, std::span<const double> data) override;
  void write(std::string_view name, std::span<const std::int64_t> data) override;
  [[nodiscard]] std::vector<double> read_f64(std::string_view name) const override;
  [[nodiscard]] std::vector<std::int64_t> read_i64(std::string_view name) const override;
  [[nodiscard]] bool has(std::string_view name) const override;

  /// Fields in name order (deterministic).
  [[nodiscard]] const std::map<std::string, Field, std::less<>>& fields() const { return fields_; }

  /// Flatten to bytes and back (for MPI transfer). Round trip is exact.
  [[nodiscard]] std::vector<char> serialize() const;
  static StateStore deserialize(std::span<const char> bytes);

 private:
  std::map<std::string, Field, std::less<>> fields_;
};

}  // namespace common
