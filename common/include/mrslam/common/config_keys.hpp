#pragma once
// An opt-in log of what config loaders ask for. While a ConfigKeyLog exists, every get*, require*,
// section and sectionList call of a Config records the full key, its kind, its default as one
// writes it in YAML and its range. The test of docs/configuration.md runs every loader with a log
// to check the reference against them. Without a log, Config records nothing.

#include <mutex>
#include <string>
#include <vector>

namespace mrslam {

enum class ConfigKeyKind {
  kNumber,       ///< getDouble / requireDouble
  kInteger,      ///< getInt / requireInt
  kBool,         ///< getBool
  kString,       ///< getString / requireString / getExpandedString
  kChoice,       ///< getChoice: one of ConfigKeyUse::choices
  kNumbers,      ///< getDoubles: a list of numbers
  kPath,         ///< getPath / requirePath
  kSection,      ///< section: a map of keys
  kSectionList,  ///< sectionList: a list of maps
};

/// "number", "integer", "bool", "string", "choice", "numbers", "path", "section", "section list".
const char* configKeyKindName(ConfigKeyKind kind);

/// One key a loader asked for.
struct ConfigKeyUse {
  std::string file;  ///< the config's file name (the name given to loadString)
  std::string key;   ///< full dotted key, list items as `name[]`: "robots[].id"
  ConfigKeyKind kind = ConfigKeyKind::kString;
  /// The default as written in YAML (0.05, 2, true, "ekf", [0, 0, 0], [] for a section list, {}
  /// for a section); "required" for require*; "unset" when the loader tested the key with has()
  /// before reading it (absent, the loader does something else than take a default). A path's
  /// default under the config's folder is given relative to it, as it would be written.
  std::string default_text;
  std::vector<std::string> choices;  ///< kChoice: the allowed values
  std::string range;                 ///< "[min, max]" when a range was given, else empty
};

/// Records ConfigKeyUse while it exists; one log at a time (a second one throws
/// std::logic_error). Loaders may run on any thread, but not while the log is destroyed.
class ConfigKeyLog {
 public:
  ConfigKeyLog();
  ~ConfigKeyLog();
  ConfigKeyLog(const ConfigKeyLog&) = delete;
  ConfigKeyLog& operator=(const ConfigKeyLog&) = delete;

  /// Every use recorded so far, in call order.
  std::vector<ConfigKeyUse> uses() const;
  void clear();

  /// Whether a log is recording (Config checks it before building a ConfigKeyUse).
  static bool recording();
  /// Adds `use` to the recording log, if any; `[N]` in its key becomes `[]`.
  static void record(ConfigKeyUse use);

 private:
  mutable std::mutex mutex_;
  std::vector<ConfigKeyUse> uses_;
};

/// A number as written in YAML: 0.05, 2, 120, 1e-6 (rounded to 15 significant digits, so a
/// default computed as 0.5 degrees from radians reads 0.5).
std::string yamlNumber(double value);
/// A double-quoted YAML string: "ekf", "".
std::string yamlString(const std::string& text);
/// A flow list of numbers: [0, 0, 0].
std::string yamlNumbers(const std::vector<double>& values);

}  // namespace mrslam
