// The DEM RVEs of a coupled job on one rank (app::DemPool): the prepared samples of the pool and
// the RVEs brought to the in-situ targets, made once and copied to every point that starts alike;
// and their preparation ahead of the farm's first create(), shared over the ranks and threads
// (docs/design/dem.md, "In-situ initial states", Where).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/job/job.hpp"
#include "app/setup/insitu.hpp"
#include "dem/rve.hpp"
#include "dem/simulation.hpp"

namespace app {

/// The prepared sample of each sample k of the pool (the preparation of [dem.sample]) and one RVE
/// per (group, sample) that the rank's points need: the sample brought by the tensor servo to the
/// group's target (app/setup/insitu.hpp), or the sample itself for a point without a target (group
/// -1). Every RVE of a point is a copy of its (group, sample) RVE. With the defaults (prepared
/// bodies, one sample) this is the one prepared sample.
class DemPool {
 public:
  /// (group, sample); group -1: the prepared sample itself.
  using Key = std::pair<std::int32_t, std::int64_t>;

  DemPool(Job job, dem::RveParams params, InsituPlan plan);

  /// The RVE of material point `id`; what it needs and prepare() did not make is made now.
  const dem::Rve& get(std::int64_t id);

  /// Collective over `comm`, every rank with the DEM point ids it will create (the farm's
  /// MicroKind::prepare; `mpmxdem run` also calls it before the farm, with the points spread
  /// over the ranks). What some rank lacks comes from the lowest rank that holds it, else it is
  /// made once, spread over the ranks (round robin over the sorted union of what nobody holds)
  /// and run on their threads; each result is sent to the ranks that need it, first the samples
  /// (save_simulation; to the ranks whose points use them and to those that prepare a group
  /// from them), then the (group, sample) RVEs (Rve::save): both continue bit for bit, so the
  /// RVEs are those get() would make alone. Rank 0 logs every preparation's lines in (sample,
  /// group) order; a failure anywhere is thrown on every rank (farm::agree_on_errors: the
  /// lowest failing rank's, the first in order there).
  void prepare(const std::vector<std::int64_t>& ids, MPI_Comm comm);

 private:
  const dem::Simulation& sample(std::int64_t k);
  void add_sample(std::int64_t k, dem::Simulation sim);
  const dem::Rve& add_rve(const Key& key, dem::Simulation sim);
  const dem::Rve& insert_rve(const Key& key, std::unique_ptr<dem::Rve> rve);
  [[nodiscard]] std::string prepare_group(dem::Simulation& sim, const Key& key) const;

  Job job_;
  dem::RveParams params_;
  InsituPlan plan_;
  std::map<std::int64_t, dem::Simulation> samples_;
  std::map<Key, std::unique_ptr<dem::Rve>> rves_;
  bool d50_set_ = false;  ///< params_.d50 is set with the first sample
};

}  // namespace app
