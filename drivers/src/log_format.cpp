#include "mrslam/drivers/log_format.hpp"

#include <array>
#include <string_view>
#include <utility>
#include <vector>

#include "mrslam/drivers/breezyslam_reader.hpp"
#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/drivers/line_reader.hpp"
#include "mrslam/drivers/mrslam_log.hpp"

namespace mrslam::drivers {
namespace {

constexpr std::size_t kDetectLineBytes = 64 * 1024;  // longer first lines are not a log we know
constexpr std::size_t kDetectMaxLines = 200;         // '#' and empty lines passed over at most
constexpr std::size_t kBreezySlamMinFields = 26;     // 25 header fields and at least one range

// Message names of CARMEN logs (carmen/src/logger and the Radish logs).
constexpr std::array<std::string_view, 22> kCarmenMessages = {
    "PARAM",       "SYNC",        "ODOM",      "FLASER",    "RLASER",    "LASER3",
    "LASER4",      "RAWLASER1",   "RAWLASER2", "RAWLASER3", "RAWLASER4", "ROBOTLASER0",
    "ROBOTLASER1", "ROBOTLASER2", "TRUEPOS",   "NEFF",      "GPSNMEA",   "GPSGGA",
    "GPSRMC",      "SONAR",       "BUMPER",    "IMU"};

bool isCarmenMessage(std::string_view name) {
  for (const std::string_view known : kCarmenMessages) {
    if (name == known) {
      return true;
    }
  }
  return false;
}

bool looksLikeBreezySlam(const std::vector<std::string_view>& fields) {
  if (fields.size() < kBreezySlamMinFields) {
    return false;
  }
  const std::optional<std::int64_t> stamp = parseInteger(fields[0]);
  if (!stamp || *stamp < 0) {
    return false;
  }
  for (const std::string_view field : fields) {
    if (!parseNumber(field)) {
      return false;
    }
  }
  return true;
}

}  // namespace

LogFormatError::LogFormatError(const std::string& path, std::size_t line,
                               const std::string& problem)
    : std::runtime_error(path + ":" + std::to_string(line) + ": " + problem),
      path_(path),
      line_(line),
      problem_(problem) {}

MalformedLineHandler::MalformedLineHandler(std::string component, MalformedPolicy policy)
    : policy_(policy), errors_(std::move(component)) {}

void MalformedLineHandler::handle(const std::string& path, std::size_t line,
                                  const LineProblem& problem) {
  if (policy_ == MalformedPolicy::kStop) {
    throw LogFormatError(path, line, problem.what);
  }
  errors_.report(problem.kind, path + ":" + std::to_string(line) + ": " + problem.what);
}

const char* logFormatName(LogFormat format) {
  switch (format) {
    case LogFormat::kBreezySlam:
      return "breezyslam";
    case LogFormat::kCarmen:
      return "carmen";
    case LogFormat::kMrslam:
      return "mrslam";
    case LogFormat::kUnknown:
      break;
  }
  return "unknown";
}

LogFormat detectLogFormat(const std::string& path) {
  LineReader lines(path, kDetectLineBytes);
  std::string line;
  std::vector<std::string_view> fields;
  for (std::size_t read = 0; read < kDetectMaxLines && lines.next(line); ++read) {
    if (lines.lastLineCut()) {
      return LogFormat::kUnknown;
    }
    if (read == 0 && line == kMrslamLogMagic) {
      return LogFormat::kMrslam;
    }
    splitFields(line, fields);
    if (fields.empty() || fields[0].front() == '#') {
      continue;
    }
    if (isCarmenMessage(fields[0])) {
      return LogFormat::kCarmen;
    }
    return looksLikeBreezySlam(fields) ? LogFormat::kBreezySlam : LogFormat::kUnknown;
  }
  return LogFormat::kUnknown;
}

std::unique_ptr<SampleSource> openLogReader(const std::string& path, MalformedPolicy policy) {
  switch (detectLogFormat(path)) {
    case LogFormat::kBreezySlam: {
      BreezySlamSettings settings;
      settings.path = path;
      settings.malformed_policy = policy;
      return std::make_unique<BreezySlamReader>(std::move(settings));
    }
    case LogFormat::kCarmen: {
      CarmenSettings settings;
      settings.path = path;
      settings.malformed_policy = policy;
      return std::make_unique<CarmenReader>(std::move(settings));
    }
    case LogFormat::kMrslam: {
      MrslamLogSettings settings;
      settings.path = path;
      settings.malformed_policy = policy;
      return std::make_unique<MrslamLogReader>(std::move(settings));
    }
    case LogFormat::kUnknown:
      break;
  }
  throw std::runtime_error(path + ": unknown log format (not an mrslam, BreezySLAM or CARMEN log)");
}

}  // namespace mrslam::drivers
