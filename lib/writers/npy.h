#pragma once
// .npy files as numpy.save writes them: format version 1.0, the header dict
// padded with spaces to a multiple of 64 bytes and ended by '\n', C order.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sdg {

// `descr` is numpy's dtype text, e.g. "'<f4'" or
// "[('semanticId', '<u4'), ('x_min', '<i4')]"; `shape` like "(512, 512)".
std::vector<uint8_t> encodeNpy(const std::string& descr, const std::string& shape, std::span<const uint8_t> data);
// "(N,)" / "(H, W)" / "(H, W, 4)" as numpy prints shapes.
std::string npyShape(std::initializer_list<size_t> dims);

}  // namespace sdg
