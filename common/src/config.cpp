#include "mrslam/common/config.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace mrslam {

struct Config::Document {
  std::string file_name;
  YAML::Node root;
  std::set<std::string> keys_read;    // full dotted keys ("laser.max_range_m", "robots[2].id")
  std::set<std::string> keys_tested;  // keys has() was asked for, while a ConfigKeyLog records
};

namespace {

bool hasBounds(Range range) {
  return std::isfinite(range.min) || std::isfinite(range.max);
}

std::string describeNumberRange(Range range) {
  std::ostringstream text;
  text << "must be in [" << range.min << ", " << range.max << "]";
  return text.str();
}

int lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line < 0 ? 1 : mark.line + 1;
}

YAML::Node parseYaml(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw ConfigError(name + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
}

}  // namespace

Config::Config(std::shared_ptr<Document> document, YAML::Node node, std::string prefix)
    : document_(std::move(document)), node_(std::move(node)), prefix_(std::move(prefix)) {}

Config Config::loadString(const std::string& text, const std::string& name) {
  auto document = std::make_shared<Document>();
  document->file_name = name;
  document->root = parseYaml(text, name);
  if (document->root.IsNull()) {
    document->root = YAML::Node(YAML::NodeType::Map);
  }
  if (!document->root.IsMap()) {
    throw ConfigError(name + ":" + std::to_string(lineOf(document->root)) +
                      ": the top level must be a map of keys");
  }
  return Config(document, document->root, "");
}

Config Config::loadFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw ConfigError(path + ": cannot open the config file");
  }
  std::stringstream text;
  text << file.rdbuf();
  return loadString(text.str(), path);
}

std::string Config::fullKey(const std::string& key) const {
  if (prefix_.empty()) {
    return key;
  }
  return key.empty() ? prefix_ : prefix_ + "." + key;
}

std::string Config::where(const std::string& key) const {
  YAML::Node node = key.empty() ? node_ : child(key);
  if (!node) {
    node = node_;
  }
  return document_->file_name + ":" + std::to_string(lineOf(node));
}

std::string Config::folder() const {
  const std::filesystem::path parent = std::filesystem::path(document_->file_name).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

YAML::Node Config::child(const std::string& key) const {
  if (!node_.IsMap()) {
    return YAML::Node();
  }
  // operator[] on a const node never inserts.
  const YAML::Node& const_node = node_;
  return const_node[key];
}

void Config::failAt(const YAML::Node& node, const std::string& key, const std::string& what) const {
  const YAML::Node& at = node ? node : node_;
  throw ConfigError(document_->file_name + ":" + std::to_string(lineOf(at)) + ": " + fullKey(key) +
                    ": " + what);
}

void Config::fail(const std::string& key, const std::string& what) const {
  failAt(child(key), key, what);
}

bool Config::present(const std::string& key) const {
  return static_cast<bool>(child(key));
}

bool Config::has(const std::string& key) const {
  if (ConfigKeyLog::recording()) {
    document_->keys_tested.insert(fullKey(key));
  }
  return present(key);
}

void Config::record(const std::string& key, ConfigKeyKind kind, std::string default_text,
                    Range range, std::vector<std::string> choices) const {
  ConfigKeyUse use;
  use.file = document_->file_name;
  use.key = fullKey(key);
  use.kind = kind;
  use.default_text = document_->keys_tested.count(use.key) != 0 ? "unset" : std::move(default_text);
  use.choices = std::move(choices);
  if (hasBounds(range)) {
    use.range = "[" + yamlNumber(range.min) + ", " + yamlNumber(range.max) + "]";
  }
  ConfigKeyLog::record(std::move(use));
}

double Config::readNumber(const std::string& key, Range range, bool integral) const {
  const YAML::Node node = child(key);
  document_->keys_read.insert(fullKey(key));
  if (!node.IsScalar()) {
    failAt(node, key, integral ? "must be an integer" : "must be a number");
  }
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    failAt(node, key,
           integral ? "must be an integer, not '" + node.Scalar() + "'"
                    : "must be a number, not '" + node.Scalar() + "'");
  }
  if (!std::isfinite(value)) {
    failAt(node, key, "must be a finite number");
  }
  if (integral && std::floor(value) != value) {
    failAt(node, key, "must be an integer, not '" + node.Scalar() + "'");
  }
  if (value < range.min || value > range.max) {
    failAt(node, key, node.Scalar() + " is out of range: " + describeNumberRange(range));
  }
  return value;
}

double Config::getDouble(const std::string& key, double default_value, Range range) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kNumber, yamlNumber(default_value), range);
  }
  document_->keys_read.insert(fullKey(key));
  return present(key) ? readNumber(key, range, false) : default_value;
}

double Config::requireDouble(const std::string& key, Range range) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kNumber, "required", range);
  }
  if (!present(key)) {
    failAt(node_, key, "is required");
  }
  return readNumber(key, range, false);
}

long long Config::getInt(const std::string& key, long long default_value, Range range) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kInteger, std::to_string(default_value), range);
  }
  document_->keys_read.insert(fullKey(key));
  return present(key) ? static_cast<long long>(readNumber(key, range, true)) : default_value;
}

long long Config::requireInt(const std::string& key, Range range) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kInteger, "required", range);
  }
  if (!present(key)) {
    failAt(node_, key, "is required");
  }
  return static_cast<long long>(readNumber(key, range, true));
}

bool Config::getBool(const std::string& key, bool default_value) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kBool, default_value ? "true" : "false");
  }
  document_->keys_read.insert(fullKey(key));
  const YAML::Node node = child(key);
  if (!node) {
    return default_value;
  }
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    if (text == "true" || text == "True" || text == "yes" || text == "on") {
      return true;
    }
    if (text == "false" || text == "False" || text == "no" || text == "off") {
      return false;
    }
  }
  failAt(node, key, "must be true or false");
}

std::string Config::getString(const std::string& key, const std::string& default_value) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kString, yamlString(default_value));
  }
  return readString(key, default_value);
}

std::string Config::readString(const std::string& key, const std::string& default_value) const {
  document_->keys_read.insert(fullKey(key));
  const YAML::Node node = child(key);
  if (!node) {
    return default_value;
  }
  if (!node.IsScalar()) {
    failAt(node, key, "must be a string");
  }
  return node.Scalar();
}

std::string Config::requireString(const std::string& key) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kString, "required");
  }
  if (!present(key)) {
    failAt(node_, key, "is required");
  }
  const std::string value = readString(key, "");
  if (value.empty()) {
    fail(key, "must not be empty");
  }
  return value;
}

std::string Config::getChoice(const std::string& key, const std::string& default_value,
                              std::initializer_list<const char*> allowed) const {
  return getChoice(key, default_value, std::vector<std::string>(allowed.begin(), allowed.end()));
}

std::string Config::getChoice(const std::string& key, const std::string& default_value,
                              const std::vector<std::string>& allowed) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kChoice, yamlString(default_value), {}, allowed);
  }
  const std::string value = readString(key, default_value);
  std::string choices;
  for (const std::string& choice : allowed) {
    if (value == choice) {
      return value;
    }
    choices += choices.empty() ? "" : ", ";
    choices += choice;
  }
  fail(key, "'" + value + "' is not one of: " + choices);
}

std::vector<double> Config::getDoubles(const std::string& key,
                                       const std::vector<double>& default_value, std::size_t size,
                                       Range range) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kNumbers, yamlNumbers(default_value), range);
  }
  document_->keys_read.insert(fullKey(key));
  const YAML::Node node = child(key);
  if (!node) {
    return default_value;
  }
  if (!node.IsSequence()) {
    failAt(node, key, "must be a list of numbers");
  }
  if (size != 0 && node.size() != size) {
    failAt(node, key, "must have exactly " + std::to_string(size) + " numbers");
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node item = node[i];
    double value = 0.0;
    try {
      value = item.as<double>();
    } catch (const YAML::Exception&) {
      failAt(item, key, "item " + std::to_string(i) + " must be a number");
    }
    if (!std::isfinite(value) || value < range.min || value > range.max) {
      failAt(item, key, "item " + std::to_string(i) + " " + describeNumberRange(range));
    }
    values.push_back(value);
  }
  return values;
}

std::string Config::getExpandedString(const std::string& key,
                                      const std::string& default_value) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kString, yamlString(default_value));
  }
  return readExpandedString(key, default_value);
}

std::string Config::readExpandedString(const std::string& key,
                                       const std::string& default_value) const {
  if (!present(key)) {
    document_->keys_read.insert(fullKey(key));
    return default_value;
  }
  const std::string text = readString(key, default_value);
  std::string expanded;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find("${", at);
    if (open == std::string::npos) {
      expanded += text.substr(at);
      break;
    }
    const std::size_t close = text.find('}', open);
    if (close == std::string::npos) {
      fail(key, "has an unterminated ${ in \"" + text + "\"");
    }
    const std::string name = text.substr(open + 2, close - open - 2);
    const char* value = name.empty() ? nullptr : std::getenv(name.c_str());
    if (value == nullptr) {
      fail(key, "names the environment variable \"" + name + "\", which is not set");
    }
    expanded += text.substr(at, open - at) + value;
    at = close + 1;
  }
  return expanded;
}

std::string Config::requirePath(const std::string& key) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kPath, "required");
  }
  if (!present(key)) {
    failAt(node_, key, "is required");
  }
  const std::string value = readPath(key, "");
  if (value.empty()) {
    fail(key, "must not be empty");
  }
  return value;
}

std::string Config::getPath(const std::string& key, const std::string& default_value) const {
  if (ConfigKeyLog::recording()) {
    // A default under the config's folder as one would write it: relative to that folder.
    std::string as_written = default_value;
    const std::filesystem::path relative =
        std::filesystem::path(default_value).lexically_relative(folder());
    if (!default_value.empty() && !relative.empty() && *relative.begin() != "..") {
      as_written = relative.string();
    }
    record(key, ConfigKeyKind::kPath, yamlString(as_written));
  }
  return readPath(key, default_value);
}

std::string Config::readPath(const std::string& key, const std::string& default_value) const {
  if (!present(key)) {
    document_->keys_read.insert(fullKey(key));
    return default_value;
  }
  const std::string value = readExpandedString(key, default_value);
  if (value.empty()) {
    return value;
  }
  const std::filesystem::path path(value);
  return path.is_absolute() ? value
                            : (std::filesystem::path(folder()) / path).lexically_normal().string();
}

Config Config::section(const std::string& key) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kSection, "{}");
  }
  document_->keys_read.insert(fullKey(key));
  const YAML::Node node = child(key);
  if (!node || node.IsNull()) {
    return Config(document_, YAML::Node(YAML::NodeType::Map), fullKey(key));
  }
  if (!node.IsMap()) {
    failAt(node, key, "must be a map of keys");
  }
  return Config(document_, node, fullKey(key));
}

std::vector<Config> Config::sectionList(const std::string& key) const {
  if (ConfigKeyLog::recording()) {
    record(key, ConfigKeyKind::kSectionList, "[]");
  }
  document_->keys_read.insert(fullKey(key));
  const YAML::Node node = child(key);
  std::vector<Config> items;
  if (!node || node.IsNull()) {
    return items;
  }
  if (!node.IsSequence()) {
    failAt(node, key, "must be a list");
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item_key = fullKey(key) + "[" + std::to_string(i) + "]";
    if (!node[i].IsMap()) {
      throw ConfigError(document_->file_name + ":" + std::to_string(lineOf(node[i])) + ": " +
                        item_key + ": must be a map of keys");
    }
    document_->keys_read.insert(item_key);
    items.push_back(Config(document_, node[i], item_key));
  }
  return items;
}

namespace {

// Depth-first search for a key in a map that nobody read.
void findUnknownKey(const YAML::Node& node, const std::string& prefix,
                    const std::set<std::string>& keys_read, const std::string& file_name) {
  if (node.IsMap()) {
    for (const auto& entry : node) {
      const std::string key = entry.first.Scalar();
      const std::string full = prefix.empty() ? key : prefix + "." + key;
      if (keys_read.count(full) == 0) {
        throw ConfigError(file_name + ":" + std::to_string(lineOf(entry.first)) + ": " + full +
                          ": unknown key");
      }
      findUnknownKey(entry.second, full, keys_read, file_name);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string item = prefix + "[" + std::to_string(i) + "]";
      if (keys_read.count(item) != 0) {
        findUnknownKey(node[i], item, keys_read, file_name);
      }
    }
  }
}

}  // namespace

void Config::checkNoUnknownKeys() const {
  findUnknownKey(document_->root, "", document_->keys_read, document_->file_name);
}

}  // namespace mrslam

namespace mrslam {

bool isValidRobotId(const std::string& robot_id) {
  if (robot_id.empty() || robot_id.size() > 64) {
    return false;
  }
  for (const char c : robot_id) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                         (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!allowed) {
      return false;
    }
  }
  return true;
}

}  // namespace mrslam
