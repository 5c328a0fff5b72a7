#pragma once
// The map mergers by name, for the tools and the fusion agent's config.

#include <memory>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

/// The names makeMerger() knows, best first.
std::vector<std::string> mergerNames();
/// The best merger there is (the first of mergerNames()).
std::string defaultMergerName();

/// A merger by name ("seed": the seed paper's pipeline, the default; "feature": the baseline;
/// "virtual": the virtual robot; "chain": steps tried in turn; "chain:STEP+STEP[+psi]": a chain
/// of the given steps, refined by ψ when `psi` ends it, its other settings the chain's), its
/// settings read from `settings`: that merger's own config section (an empty Config gives the
/// defaults). Throws std::invalid_argument for an unknown name (the message lists the known ones)
/// and ConfigError for bad settings.
std::unique_ptr<MapMerger> makeMerger(const std::string& name, const Config& settings);
/// A merger by name from a document (or section) of merger settings holding one section per
/// method (`seed:`, `virtual:`, `chain:` ...): a chain's steps take the settings of their own
/// sections there. makeMerger(name, settings) gives a chain's steps their defaults. A variant
/// "chain:STEP+STEP[+psi]" takes the `chain:` section's settings with its own steps and ψ
/// refinement, so that several chains are scored side by side in one run.
std::unique_ptr<MapMerger> makeMergerFrom(const std::string& name, const Config& methods);
/// Checks a document of merger settings with one section per method name (`feature:`, `seed:`):
/// builds each method whose section is present, then rejects every key nobody read, so a bad value,
/// an unknown key or an unknown method stops here with ConfigError.
void checkMergerConfig(const Config& config);

/// The same with default settings.
std::unique_ptr<MapMerger> makeMerger(const std::string& name);

}  // namespace mrslam::fusion
