#include "writers/npy.h"

namespace sdg {

std::string npyShape(std::initializer_list<size_t> dims) {
  std::string s = "(";
  size_t i = 0;
  for (size_t d : dims) {
    if (i++) s += ", ";
    s += std::to_string(d);
  }
  if (dims.size() == 1) s += ",";
  return s + ")";
}

std::vector<uint8_t> encodeNpy(const std::string& descr, const std::string& shape, std::span<const uint8_t> data) {
  std::string header = "{'descr': " + descr + ", 'fortran_order': False, 'shape': " + shape + ", }";
  // magic (6) + version (2) + length (2) + header + '\n', padded to 64.
  size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::vector<uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
  out.push_back(uint8_t(header.size() & 0xff));
  out.push_back(uint8_t(header.size() >> 8));
  out.insert(out.end(), header.begin(), header.end());
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

}  // namespace sdg
