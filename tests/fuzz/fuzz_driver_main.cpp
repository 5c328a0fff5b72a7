// A small stand-in for libFuzzer's driver, for compilers without it: feeds the target the files
// of a corpus folder and seeded random mutations of them (byte flips, insertions, deletions,
// truncations, splices). A crash or an uncaught exception fails the run.
//   <target>_fuzz [--runs N] [--seed S] [corpus folder]

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Input = std::vector<std::uint8_t>;

std::vector<Input> loadCorpus(const std::string& folder) {
  std::vector<Input> corpus;
  if (folder.empty() || !std::filesystem::is_directory(folder)) {
    return corpus;
  }
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    std::ifstream file(entry.path(), std::ios::binary);
    corpus.emplace_back(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  return corpus;
}

Input mutate(const std::vector<Input>& corpus, std::mt19937_64& random) {
  Input input = corpus.empty() ? Input{} : corpus[random() % corpus.size()];
  const int mutations = 1 + static_cast<int>(random() % 8);
  for (int m = 0; m < mutations; ++m) {
    const std::size_t at = input.empty() ? 0 : random() % input.size();
    switch (random() % 6) {
      case 0:  // flip a bit
        if (!input.empty()) {
          input[at] ^= static_cast<std::uint8_t>(1u << (random() % 8));
        }
        break;
      case 1:  // random byte
        if (!input.empty()) {
          input[at] = static_cast<std::uint8_t>(random());
        }
        break;
      case 2:  // insert bytes
        input.insert(input.begin() + static_cast<std::ptrdiff_t>(at), 1 + random() % 4,
                     static_cast<std::uint8_t>(random()));
        break;
      case 3:  // delete bytes
        if (!input.empty()) {
          const std::size_t count = std::min<std::size_t>(1 + random() % 8, input.size() - at);
          input.erase(input.begin() + static_cast<std::ptrdiff_t>(at),
                      input.begin() + static_cast<std::ptrdiff_t>(at + count));
        }
        break;
      case 4:  // truncate
        input.resize(at);
        break;
      default:  // splice in a piece of another corpus entry
        if (!corpus.empty()) {
          const Input& other = corpus[random() % corpus.size()];
          if (!other.empty()) {
            const std::size_t from = random() % other.size();
            const std::size_t count = std::min<std::size_t>(1 + random() % 64, other.size() - from);
            input.insert(input.begin() + static_cast<std::ptrdiff_t>(at),
                         other.begin() + static_cast<std::ptrdiff_t>(from),
                         other.begin() + static_cast<std::ptrdiff_t>(from + count));
          }
        }
        break;
    }
  }
  return input;
}

}  // namespace

int main(int argc, char** argv) {
  long runs = 10000;
  std::uint64_t seed = 1;
  std::string corpus_folder;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::atol(argv[++i]);
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      corpus_folder = argv[i];
    }
  }
  const std::vector<Input> corpus = loadCorpus(corpus_folder);
  for (const Input& input : corpus) {
    LLVMFuzzerTestOneInput(input.data(), input.size());
  }
  std::mt19937_64 random(seed);
  for (long run = 0; run < runs; ++run) {
    const Input input = mutate(corpus, random);
    LLVMFuzzerTestOneInput(input.data(), input.size());
  }
  std::printf("%zu corpus inputs and %ld mutations ran without a crash\n", corpus.size(), runs);
  return 0;
}
