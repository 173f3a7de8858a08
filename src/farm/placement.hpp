// Where the RVEs live: RVE index k (position of its id in the ascending id list) -> owner rank,
// this rank's indices and every rank's members; and PointIndex, the map from the MPM solver's
// point slots to RVE indices.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/types.hpp"

namespace farm {

/// Ownership of the RVEs over `size` ranks, seen from `rank`. Indices are positions in ids()
/// (ascending, unique); every list below is in ascending index order. Only the worker ranks
/// [first_worker, size) own RVEs: first_worker = 1 leaves rank 0 to the MPM alone
/// (`farm.rank0_rves = false`). The partitioners work on parts [0, workers()): parts() and
/// owners_of() translate.
class Placement {
 public:
  Placement() = default;
  /// Starts with contiguous blocks (partition_blocks) over the worker ranks. Throws
  /// common::InternalError unless `ids` is ascending and unique.
  /// @pre 0 <= rank < size, 0 <= first_worker < size
  Placement(std::vector<std::int64_t> ids, int rank, int size, int first_worker = 0);

  [[nodiscard]] const std::vector<std::int64_t>& ids() const { return ids_; }
  [[nodiscard]] std::size_t size() const { return ids_.size(); }
  [[nodiscard]] const std::vector<int>& owner() const { return owner_; }
  /// The RVE indices of this rank.
  [[nodiscard]] const std::vector<std::size_t>& local() const { return members_[rank_u()]; }
  /// The RVE indices of rank r.
  [[nodiscard]] const std::vector<std::size_t>& members(int r) const {
    return members_[static_cast<std::size_t>(r)];
  }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int nranks() const { return nranks_; }
  /// The lowest rank that owns RVEs (0 or 1).
  [[nodiscard]] int first_worker() const { return first_worker_; }
  /// The number of ranks that may own RVEs (the partitioners' parts).
  [[nodiscard]] int workers() const { return nranks_ - first_worker_; }
  /// owner() as parts in [0, workers()).
  [[nodiscard]] std::vector<int> parts() const;
  /// The owner ranks of parts in [0, workers()).
  [[nodiscard]] std::vector<int> owners_of(std::vector<int> parts) const;
  /// Index of RVE `id`; throws common::InternalError if there is none.
  [[nodiscard]] std::size_t index_of(std::int64_t id) const;
  /// RVEs whose owner differs between owner() and `new_owner`.
  [[nodiscard]] std::int64_t moves_to(const std::vector<int>& new_owner) const;
  /// Adopts new owners (one rank per index, each in [first_worker, nranks)).
  void set_owner(std::vector<int> owner);

 private:
  [[nodiscard]] std::size_t rank_u() const { return static_cast<std::size_t>(rank_); }
  std::vector<std::int64_t> ids_;
  std::vector<int> owner_;
  std::vector<std::vector<std::size_t>> members_;  ///< by rank
  int rank_ = 0;
  int nranks_ = 1;
  int first_worker_ = 0;
};

/// Point slot p of the solver's point list -> RVE index k (ids ascending), built once from the
/// point ids and reused while the solver hands its points in the same order.
class PointIndex {
 public:
  PointIndex() = default;
  /// Throws common::InternalError if a point id has no RVE, or if an RVE id is given twice or
  /// not at all (every RVE is one point and every point one RVE).
  PointIndex(std::span<const std::int64_t> rve_ids, std::span<const std::int64_t> point_ids);
  /// True when `point_ids` is the list this index was built from (a cheap check per step).
  [[nodiscard]] bool matches(std::span<const std::int64_t> point_ids) const;
  [[nodiscard]] std::size_t rve_of(std::size_t slot) const { return rve_of_[slot]; }
  [[nodiscard]] std::size_t slot_of(std::size_t rve) const { return slot_of_[rve]; }
  [[nodiscard]] std::size_t size() const { return rve_of_.size(); }
  /// Values given by slot, returned by RVE index.
  template <class T>
  [[nodiscard]] std::vector<T> by_rve(std::span<const T> by_slot) const {
    std::vector<T> out(by_slot.size());
    for (std::size_t p = 0; p < by_slot.size(); ++p) out[rve_of_[p]] = by_slot[p];
    return out;
  }

 private:
  std::vector<std::int64_t> point_ids_;
  std::vector<std::size_t> rve_of_;   ///< by slot
  std::vector<std::size_t> slot_of_;  ///< by RVE index
};

}  // namespace farm
