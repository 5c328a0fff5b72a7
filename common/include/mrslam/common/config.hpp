#pragma once
// Validated YAML configuration. Every value is read by name with its type and allowed range;
// what is wrong stops the program with `file:line: key: what is wrong`. After a loader has read
// everything it knows, checkNoUnknownKeys() rejects every key nobody asked for. While a
// ConfigKeyLog exists (config_keys.hpp), every read is also recorded for the configuration
// reference's test.

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrslam/common/config_keys.hpp"

namespace mrslam {

/// A configuration error; what() is `file:line: key: what is wrong`.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Inclusive bounds of a numeric value.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

/// One map node of a config document, with the document's bookkeeping of which keys were read.
class Config {
 public:
  /// Loads a YAML file; its top level must be a map (an empty file is an empty map).
  static Config loadFile(const std::string& path);
  /// Loads YAML text; `name` stands for the file name in messages.
  static Config loadString(const std::string& text, const std::string& name);

  /// Whether `key` is present. A ConfigKeyLog records a key tested this way and read afterwards
  /// as having no default ("unset"): the loader does something else when it is absent.
  bool has(const std::string& key) const;

  double getDouble(const std::string& key, double default_value, Range range = {}) const;
  double requireDouble(const std::string& key, Range range = {}) const;
  long long getInt(const std::string& key, long long default_value, Range range = {}) const;
  long long requireInt(const std::string& key, Range range = {}) const;
  bool getBool(const std::string& key, bool default_value) const;
  std::string getString(const std::string& key, const std::string& default_value) const;
  std::string requireString(const std::string& key) const;
  /// A string that must be one of `allowed`.
  std::string getChoice(const std::string& key, const std::string& default_value,
                        std::initializer_list<const char*> allowed) const;
  std::string getChoice(const std::string& key, const std::string& default_value,
                        const std::vector<std::string>& allowed) const;
  /// A list of exactly `size` numbers (any size when size is 0).
  std::vector<double> getDoubles(const std::string& key, const std::vector<double>& default_value,
                                 std::size_t size = 0, Range range = {}) const;
  /// A file path; a relative path in the file is taken relative to the config file's folder
  /// (the default is returned as given). `${NAME}` in the value is replaced by the environment
  /// variable NAME first (an unset NAME is an error naming it).
  std::string getPath(const std::string& key, const std::string& default_value) const;
  /// A required path (a device, a file), read as getPath reads it.
  std::string requirePath(const std::string& key) const;
  /// A string with `${NAME}` replaced by the environment variable NAME (e.g. a library name).
  std::string getExpandedString(const std::string& key, const std::string& default_value) const;

  /// A nested map; a missing key gives an empty section (every value takes its default).
  Config section(const std::string& key) const;
  /// A list of maps (missing: empty list).
  std::vector<Config> sectionList(const std::string& key) const;

  /// Throws for the first key in the document that no reader asked for.
  void checkNoUnknownKeys() const;
  /// Throws a ConfigError about `key` in this section.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  /// `file:line` of this section (or of `key` in it, when present).
  std::string where(const std::string& key = "") const;
  /// The folder of the config file (for relative paths).
  std::string folder() const;

 private:
  struct Document;
  Config(std::shared_ptr<Document> document, YAML::Node node, std::string prefix);

  YAML::Node child(const std::string& key) const;
  bool present(const std::string& key) const;
  // The readers without recording (the public ones record, then call these).
  std::string readString(const std::string& key, const std::string& default_value) const;
  std::string readExpandedString(const std::string& key, const std::string& default_value) const;
  std::string readPath(const std::string& key, const std::string& default_value) const;
  // Records a use of `key` when a ConfigKeyLog is recording (callers check recording() first).
  void record(const std::string& key, ConfigKeyKind kind, std::string default_text,
              Range range = {}, std::vector<std::string> choices = {}) const;
  std::string fullKey(const std::string& key) const;
  [[noreturn]] void failAt(const YAML::Node& node, const std::string& key,
                           const std::string& what) const;
  double readNumber(const std::string& key, Range range, bool integral) const;

  std::shared_ptr<Document> document_;
  YAML::Node node_;
  std::string prefix_;
};

}  // namespace mrslam

namespace mrslam {

/// Robot ids name topics' instances and files: 1 to 64 characters of [A-Za-z0-9_-].
bool isValidRobotId(const std::string& robot_id);

}  // namespace mrslam
