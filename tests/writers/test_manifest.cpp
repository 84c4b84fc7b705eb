// The manifest's index: which line counts for each (frame, product) across
// a folder's manifests, and the canonical manifest streamed from it.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/file_io.h"
#include "scratch_name.h"
#include "writers/manifest.h"

namespace fs = std::filesystem;

namespace {

std::string line(uint64_t frame, uint32_t product, const std::string& file) {
  sdg::ManifestEntry e;
  e.frame = frame;
  e.product = product;
  e.files.push_back({file, 3, std::string(64, 'a')});
  return e.toLine();
}

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("manifest index: sorted, one line per frame and product, a later line wins, torn and bad lines skipped",
          "[manifest]") {
  const sdg::test::ScratchFolder scratch("manifest_index");
  const fs::path& dir = scratch.path();
  writeText(dir / "manifest.0.jsonl", line(2, 0, "b_old") + line(0, 0, "a") + "not json\n" + line(1, 1, "c"));
  // The second shard's file redoes frame 2, then ends in a torn line.
  const std::string torn = line(3, 0, "torn");
  writeText(dir / "manifest.1.jsonl", line(2, 0, "b_new") + line(1, 0, "d") + torn.substr(0, torn.size() - 1));

  const sdg::ManifestIndex index = sdg::indexManifests(dir.string());
  REQUIRE(index.files.size() == 2);
  REQUIRE(index.lines.size() == 4);
  std::vector<std::string> order;
  sdg::forEachManifestEntry(index, [&](const sdg::ManifestEntry& e) {
    order.push_back(std::to_string(e.frame) + "/" + std::to_string(e.product) + ":" + e.files.at(0).path);
  });
  CHECK(order == std::vector<std::string>{"0/0:a", "1/0:d", "1/1:c", "2/0:b_new"});

  sdg::writeCanonicalManifest(dir.string(), index);
  CHECK(readText(dir / "manifest.jsonl") == line(0, 0, "a") + line(1, 0, "d") + line(1, 1, "c") + line(2, 0, "b_new"));
  CHECK_FALSE(fs::exists(dir / "manifest.0.jsonl"));
  CHECK_FALSE(fs::exists(dir / "manifest.1.jsonl"));
  // The canonical file indexes to itself.
  CHECK(sdg::readManifests(dir.string()).size() == 4);
}

TEST_CASE("atomic file writer: whole file or none", "[manifest]") {
  const sdg::test::ScratchFolder scratch("atomic_writer");
  const fs::path& dir = scratch.path();
  {
    sdg::AtomicFileWriter unfinished((dir / "never.txt").string());
    unfinished.append(std::string_view("partial"));
  }
  CHECK(fs::is_empty(dir));  // neither the file nor its temporary

  const std::string big(200'000, 'x');  // past the direct-write size
  sdg::AtomicFileWriter file((dir / "out.txt").string());
  file.append(std::string_view("head "));
  file.append(big);
  file.append(std::string_view(" tail"));
  CHECK_FALSE(fs::exists(dir / "out.txt"));  // nothing under the final name before commit
  file.commit();
  CHECK(readText(dir / "out.txt") == "head " + big + " tail");
  CHECK_THROWS_WITH(file.append(std::string_view("late")), Catch::Contains("after it was committed"));
}
