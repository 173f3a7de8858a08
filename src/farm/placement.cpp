// Placement and PointIndex (see header).
#include "farm/placement.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "farm/partition.hpp"

namespace farm {

namespace {

/// Index of `id` in the ascending `ids`, or throws naming the id.
std::size_t find_index(std::span<const std::int64_t> ids, std::int64_t id) {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  MPMXDEM_CHECK(it != ids.end() && *it == id, "point id " + std::to_string(id) + " has no RVE");
  return static_cast<std::size_t>(it - ids.begin());
}

}  // namespace

Placement::Placement(std::vector<std::int64_t> ids, int rank, int size, int first_worker)
    : ids_(std::move(ids)), rank_(rank), nranks_(size), first_worker_(first_worker) {
  MPMXDEM_CHECK(std::is_sorted(ids_.begin(), ids_.end()) &&
                    std::adjacent_find(ids_.begin(), ids_.end()) == ids_.end(),
                "RVE ids must be ascending and unique");
  MPMXDEM_CHECK(size >= 1 && rank >= 0 && rank < size, "rank out of range");
  MPMXDEM_CHECK(first_worker >= 0 && first_worker < size, "first worker rank out of range");
  set_owner(owners_of(partition_blocks(ids_.size(), workers())));
}

std::vector<int> Placement::parts() const {
  std::vector<int> part(owner_);
  for (int& p : part) p -= first_worker_;
  return part;
}

std::vector<int> Placement::owners_of(std::vector<int> parts) const {
  for (int& p : parts) p += first_worker_;
  return parts;
}

std::size_t Placement::index_of(std::int64_t id) const { return find_index(ids_, id); }

std::int64_t Placement::moves_to(const std::vector<int>& new_owner) const {
  std::int64_t moved = 0;
  for (std::size_t k = 0; k < owner_.size(); ++k) moved += new_owner[k] != owner_[k] ? 1 : 0;
  return moved;
}

void Placement::set_owner(std::vector<int> owner) {
  MPMXDEM_CHECK(owner.size() == ids_.size(), "one owner per RVE");
  owner_ = std::move(owner);
  members_.assign(static_cast<std::size_t>(nranks_), {});
  for (std::size_t k = 0; k < owner_.size(); ++k) {
    MPMXDEM_CHECK(owner_[k] >= first_worker_ && owner_[k] < nranks_, "owner rank out of range");
    members_[static_cast<std::size_t>(owner_[k])].push_back(k);
  }
}

PointIndex::PointIndex(std::span<const std::int64_t> rve_ids,
                       std::span<const std::int64_t> point_ids)
    : point_ids_(point_ids.begin(), point_ids.end()) {
  MPMXDEM_CHECK(point_ids.size() == rve_ids.size(),
                "every RVE id once (got " + std::to_string(point_ids.size()) + " points for " +
                    std::to_string(rve_ids.size()) + " RVEs)");
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  slot_of_.assign(rve_ids.size(), kNone);
  rve_of_.resize(point_ids.size());
  for (std::size_t p = 0; p < point_ids.size(); ++p) {
    const std::size_t k = find_index(rve_ids, point_ids[p]);
    MPMXDEM_CHECK(slot_of_[k] == kNone,
                  "point id " + std::to_string(point_ids[p]) + " given twice");
    slot_of_[k] = p;
    rve_of_[p] = k;
  }
}

bool PointIndex::matches(std::span<const std::int64_t> point_ids) const {
  return std::equal(point_ids.begin(), point_ids.end(), point_ids_.begin(), point_ids_.end());
}

}  // namespace farm
