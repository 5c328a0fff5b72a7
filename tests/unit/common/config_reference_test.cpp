// The configuration reference, docs/configuration.md, against the loaders: every key a loader
// asks for has a row, every row names a key some loader asks for, and each row's default is the
// loader's. The loaders (robot agent, fusion agent, team file) run with a ConfigKeyLog on every
// config/*.yaml of their kind and on small files that reach their optional sections and branches.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/fusion_config.hpp"
#include "mrslam/robot/robot_config.hpp"
#include "mrslam/tools/team_spec.hpp"
#include "test_data.hpp"

namespace mrslam {
namespace {

namespace fs = std::filesystem;

constexpr const char* kReference = "docs/configuration.md";

enum class FileKind { kRobot, kFusion, kTeam };

// The level-2 heading of each kind's tables in the reference.
const std::map<FileKind, std::string> kHeadings = {
    {FileKind::kRobot, "Robot agent config"},
    {FileKind::kFusion, "Fusion agent config"},
    {FileKind::kTeam, "Team file"},
};

// What the loaders asked for about one key, over every file of a kind.
struct LoaderKey {
  ConfigKeyKind kind = ConfigKeyKind::kString;
  std::map<std::string, std::string> defaults;  // default text -> a file that gave it
  std::vector<std::string> choices;
};
using LoaderKeys = std::map<std::string, LoaderKey>;

// One table row of the reference.
struct DocRow {
  std::string key;
  std::string default_cell;
  std::string meaning;
  int line = 0;
};

std::string trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) {
    return "";
  }
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The text of a cell that is one code span (`text`), else nothing.
bool codeSpan(const std::string& cell, std::string& text) {
  if (cell.size() < 2 || cell.front() != '`' || cell.back() != '`') {
    return false;
  }
  text = cell.substr(1, cell.size() - 2);
  return text.find('`') == std::string::npos;
}

// The cells of a table row `| a | b | c |`; `\|` is a | inside a cell.
std::vector<std::string> splitRow(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size() && row[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (row[i] == '|') {
      cells.push_back(trim(cell));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  if (!trim(cell).empty()) {
    cells.push_back(trim(cell));  // a row without its closing |
  }
  return cells;
}

std::string reference(int line) {
  return std::string(kReference) + ":" + std::to_string(line);
}

// The key rows of each kind's tables; a malformed row is a test failure.
std::map<FileKind, std::vector<DocRow>> readReference() {
  std::map<FileKind, std::vector<DocRow>> rows;
  std::ifstream file(test::sourcePath(kReference));
  EXPECT_TRUE(file) << kReference << ": cannot open it";
  std::optional<FileKind> kind;
  std::string text;
  int line = 0;
  while (std::getline(file, text)) {
    ++line;
    if (text.rfind("## ", 0) == 0) {
      kind.reset();
      for (const auto& [candidate, heading] : kHeadings) {
        if (trim(text.substr(3)) == heading) {
          kind = candidate;
        }
      }
      continue;
    }
    if (!kind || text.rfind("|", 0) != 0) {
      continue;
    }
    std::vector<std::string> cells = splitRow(text);
    if (cells.size() != 3) {
      ADD_FAILURE() << reference(line) << ": a row has three cells (key, default, meaning)";
      continue;
    }
    if (cells[0] == "key" || cells[0].find_first_not_of("-: ") == std::string::npos) {
      continue;  // header and separator rows
    }
    DocRow row;
    if (!codeSpan(cells[0], row.key)) {
      ADD_FAILURE() << reference(line) << ": the key cell must be the key in backticks, not "
                    << cells[0];
      continue;
    }
    row.default_cell = cells[1];
    row.meaning = cells[2];
    row.line = line;
    if (row.meaning.empty()) {
      ADD_FAILURE() << reference(line) << ": `" << row.key << "` has no meaning";
    }
    rows[*kind].push_back(row);
  }
  return rows;
}

// Runs `load` on `path` with a ConfigKeyLog and adds what it asked for to `keys`.
void collect(const std::string& path, const std::function<void(const std::string&)>& load,
             LoaderKeys& keys) {
  ConfigKeyLog log;
  try {
    load(path);
  } catch (const std::exception& error) {
    ADD_FAILURE() << path << ": the loader refused it: " << error.what();
  }
  for (const ConfigKeyUse& use : log.uses()) {
    if (use.kind == ConfigKeyKind::kSection) {
      continue;  // a map of keys: the reference's headings, not a row
    }
    LoaderKey& key = keys[use.key];
    key.kind = use.kind;
    key.defaults.emplace(use.default_text, use.file);
    key.choices = use.choices;
  }
}

// robot_id: a robot config; fusion agents or a split: a team file; else a fusion config.
FileKind kindOf(const std::string& path) {
  const YAML::Node root = YAML::LoadFile(path);
  if (root["robot_id"]) {
    return FileKind::kRobot;
  }
  if (root["fusion"] || root["split"]) {
    return FileKind::kTeam;
  }
  if (const YAML::Node robots = root["robots"]; robots && robots.IsSequence()) {
    for (const YAML::Node& robot : robots) {
      if (robot.IsMap() && robot["config"]) {
        return FileKind::kTeam;
      }
    }
  }
  return FileKind::kFusion;
}

// Small files that turn on what the project's configs leave off: every default of the optional
// sections, every device, every list item, every merger, every team entry.
const std::map<FileKind, std::map<std::string, std::string>> kExtraFiles = {
    {FileKind::kRobot,
     {
         {"robot_minimal.yaml", "robot_id: r\n"},
         {"robot_devices.yaml",
          "robot_id: r\n"
          "source:\n"
          "  type: devices\n"
          "  devices:\n"
          "    laser: {device: /dev/ttyACM0}\n"
          "    imu: {device: /dev/ttyS0}\n"
          "    encoders: {library: libphidget22.so.0}\n"},
     }},
    {FileKind::kFusion,
     {
         {"fusion_minimal.yaml", ""},
         {"fusion_everything.yaml",
          "reference_robot: a\n"
          "robots:\n"
          "  - id: b\n"
          "expected_robots:\n"
          "  - id: a\n"
          "limits:\n"
          "  allowed_robots:\n"
          "    - id: a\n"
          "merge:\n"
          "  method: seed\n"
          "  seed: {}\n"
          "  feature: {}\n"
          "  virtual: {}\n"
          "  exhaustive: {}\n"
          "  psi_walk: {}\n"
          "  chain: {}\n"},
     }},
    {FileKind::kTeam,
     {
         {"team_minimal.yaml", "robots:\n  - config: robot.yaml\n"},
         {"team_everything.yaml",
          "domain_id: 7\n"
          "split:\n"
          "  log: intel.log.gz\n"
          "  segments: 2\n"
          "security_dir: pki\n"
          "discovery_server: {}\n"
          "robots:\n"
          "  - config: robot.yaml\n"
          "    segment: 1\n"
          "  - config: robot.yaml\n"
          "    id: b\n"
          "    emulate: sim.yaml\n"
          "    emulate_log: sim.log\n"
          "    emulate_duration_s: 10\n"
          "  - config: robot.yaml\n"
          "    id: c\n"
          "    log: c.log\n"
          "fusion:\n"
          "  - config: fusion.yaml\n"},
     }},
};

class ConfigReferenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // config/emulated_robot.yaml names its devices through these (a team launcher sets them).
    ::setenv("MRSLAM_DEVICE_DIR", "/tmp/mrslam-devices", 0);
    ::setenv("MRSLAM_BIN_DIR", "/tmp/mrslam-bin", 0);
  }

  // What the loader of `kind` asks for over config/*.yaml of that kind and the extra files.
  LoaderKeys loaderKeys(FileKind kind) {
    const std::map<FileKind, std::function<void(const std::string&)>> loaders = {
        {FileKind::kRobot, [](const std::string& path) { robot::loadRobotConfig(path); }},
        {FileKind::kFusion, [](const std::string& path) { fusion::loadFusionConfig(path); }},
        {FileKind::kTeam, [](const std::string& path) { tools::loadTeamSpec(path); }},
    };
    LoaderKeys keys;
    int project_files = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(test::sourcePath("config"))) {
      const std::string path = entry.path().string();
      if (entry.is_regular_file() && entry.path().extension() == ".yaml" && kindOf(path) == kind) {
        collect(path, loaders.at(kind), keys);
        ++project_files;
      }
    }
    EXPECT_GT(project_files, 0) << "no " << kHeadings.at(kind) << " in config/";
    const fs::path folder = test::scratchFolder("configs");
    for (const auto& [name, text] : kExtraFiles.at(kind)) {
      std::ofstream(folder / name) << text;
      collect((folder / name).string(), loaders.at(kind), keys);
    }
    return keys;
  }

  void checkKind(FileKind kind) {
    const std::string& heading = kHeadings.at(kind);
    const LoaderKeys keys = loaderKeys(kind);
    const std::vector<DocRow> rows = readReference()[kind];
    ASSERT_FALSE(keys.empty());

    std::map<std::string, const DocRow*> documented;
    for (const DocRow& row : rows) {
      if (!documented.emplace(row.key, &row).second) {
        ADD_FAILURE() << reference(row.line) << ": `" << row.key << "` is documented twice under "
                      << heading;
      }
    }
    for (const auto& [key, asked] : keys) {
      if (documented.count(key) == 0) {
        const auto& [first_default, first_file] = *asked.defaults.begin();
        ADD_FAILURE() << kReference << " (" << heading << "): `" << key
                      << "` is not documented; the loader reads it from " << first_file << " ("
                      << configKeyKindName(asked.kind) << ", default " << first_default << ")";
      }
    }
    for (const DocRow& row : rows) {
      const auto asked = keys.find(row.key);
      if (asked == keys.end()) {
        ADD_FAILURE() << reference(row.line) << ": `" << row.key << "` is documented under "
                      << heading << ", but its loader asks for no such key in config/*.yaml "
                      << "or the test's files";
        continue;
      }
      checkDefault(row, asked->second);
      for (const std::string& choice : asked->second.choices) {
        if (row.meaning.find("`" + choice + "`") == std::string::npos) {
          ADD_FAILURE() << reference(row.line) << ": `" << row.key << "`: the meaning does not "
                        << "name the allowed value `" << choice << "`";
        }
      }
    }
  }

  // A row's default: the loader's in backticks (`0.05`), `required`, `unset`, or, for a default
  // the loader computes from the file (differing between files), a description in words.
  static void checkDefault(const DocRow& row, const LoaderKey& asked) {
    const auto& [loader_default, file] = *asked.defaults.begin();
    std::string literal;
    const bool is_literal = codeSpan(row.default_cell, literal);
    const bool is_word = row.default_cell == "required" || row.default_cell == "unset";
    if (asked.defaults.size() > 1) {
      std::string seen;
      for (const auto& [text, where] : asked.defaults) {
        seen += (seen.empty() ? "" : ", ") + text + " in " + where;
      }
      EXPECT_FALSE(is_literal || is_word)
          << reference(row.line) << ": `" << row.key << "`: the loader's default depends on the "
          << "file (" << seen << "); describe it in words, not as " << row.default_cell;
      return;
    }
    if (loader_default == "required" || loader_default == "unset") {
      EXPECT_EQ(row.default_cell, loader_default)
          << reference(row.line) << ": `" << row.key << "`: documented default " << row.default_cell
          << ", the loader's is " << loader_default << " (" << file << ")";
      return;
    }
    EXPECT_TRUE(is_literal && literal == loader_default)
        << reference(row.line) << ": `" << row.key << "`: documented default " << row.default_cell
        << ", the loader's is `" << loader_default << "` (" << file << ")";
  }
};

TEST_F(ConfigReferenceTest, RobotAgentConfigMatchesItsLoader) {
  checkKind(FileKind::kRobot);
}

TEST_F(ConfigReferenceTest, FusionAgentConfigMatchesItsLoader) {
  checkKind(FileKind::kFusion);
}

TEST_F(ConfigReferenceTest, TeamFileMatchesItsLoader) {
  checkKind(FileKind::kTeam);
}

TEST_F(ConfigReferenceTest, ConfigFolderHoldsEveryKindOfFile) {
  // Each kind's check runs its loader on config/*.yaml of that kind (a refused file fails it).
  std::set<FileKind> kinds;
  for (const fs::directory_entry& entry : fs::directory_iterator(test::sourcePath("config"))) {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
      kinds.insert(kindOf(entry.path().string()));
    }
  }
  EXPECT_EQ(kinds.size(), kHeadings.size());
}

}  // namespace
}  // namespace mrslam
