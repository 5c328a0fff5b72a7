#pragma once
// Known-answer crop pairs of the shared maps, cut as `mrslam merge-cases` cuts them, for the seed
// merger's tests of single cases (the same case numbers as its --json --details output).

#include <string>

#include "mrslam/common/map_loaders.hpp"
#include "mrslam/fusion/merge/merge_cases.hpp"
#include "test_data.hpp"

namespace mrslam::fusion::merge_test {

struct CropPair {
  const char* map;
  int case_id;
  CropSpec a;
  CropSpec b;
};

inline MergeCase cut(const CropPair& pair) {
  const SourceMap source{pair.map, "one building",
                         loadMapFile(test::sharedDataPath(std::string("maps/") + pair.map))};
  MergeCase merge_case = makeCase(source, pair.a, source, pair.b);
  merge_case.id = pair.case_id;
  return merge_case;
}

}  // namespace mrslam::fusion::merge_test
