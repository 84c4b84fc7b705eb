#pragma once
// Low-discrepancy sample streams for the path tracer: Owen-scrambled Sobol
// points padded in dimension pairs (Burley 2020, "Practical Hash-based Owen
// Scrambling"), ordered across the image as Ahmed and Wonka's Z-sampler
// (2020, "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error
// via Hierarchical Ordering of Pixels"; pbrt-v4's ZSobolSampler is the best
// known implementation) so that neighbouring pixels share one net.
//
// Every draw (a next2D() pair or a next1D() value) takes the next
// "dimension slot" of the sample. Each slot uses the first two Sobol
// dimensions, which form a (0,2)-sequence in base 2, with
// - its own shuffle of the sample index, so slots are decorrelated from one
//   another, and
// - its own nested uniform (Owen) scramble of each coordinate, done with a
//   Laine-Karras style hash.
// The points of an aligned block of 2^m indices [k 2^m, (k+1) 2^m) form a
// (0,m,2)-net: every elementary interval of area 2^-m holds exactly one
// point. Both scrambles keep that for the blocks below (the shuffle maps
// each onto another aligned block).
//
// The Z-order: sample s of pixel (x, y) is Sobol index
//   (morton(x mod T, y mod T) << sampleBits) | s,
// sampleBits = ceil(log2(samples per pixel)), T = 2^tileBits the side of a
// square tile. A pixel's samples are one aligned block (and so are its
// samples' aligned power-of-two runs), and so are those of every aligned
// 2^k x 2^k block of pixels within a tile: the block's
// 4^k x spp points of a slot form a net too, so the errors of neighbouring
// pixels cancel (a block mean converges like quasi-Monte Carlo; the error
// image is blue noise, which the denoiser averages away better). The
// scrambles' keys are hashed from (frame seed, tile, slot), not the pixel:
// distant tiles are independent, pixels of one tile share keys. Sobol
// indices are 32 bits: tileBits = min(6, (32 - sampleBits) / 2), so 64 x 64
// tiles up to 2^20 samples per pixel, smaller ones beyond (a tile of one
// pixel at 2^31). A sample count not a power of two leaves indices unused.
//
// The index shuffle first permutes each 2 x 2 quad's four sub-blocks among
// its pixels by any of the 24 permutations (permuteQuads(), as pbrt-v4
// permutes base-4 digits), then flips bits as a nested base-2 scramble. The
// scramble alone gives 8 of the 24 and always keeps the same two pixels of a
// quad in one half-block: a frame's error came out in vertical stripes
// (docs/rendering.md).
//
// A stream depends only on (frame seed, samples per pixel, pixel x, y,
// sample index, slot): never on the thread that draws it, the order pixels
// are drawn in, nor how a frame's samples are split into batches. The GPU
// tracer draws the same numbers (gpu/shaders/pt_common.glsl).
//
// Speed: a slot's keys depend on the tile and the slot, not on the pixel
// or sample, so a SamplerTile works them out once for its first
// kCachedSlots slots and all its pixels' samples reuse them; the quads'
// permutation of a pixel's Morton code depends on the pixel and the slot,
// so a PixelSampler keeps it from its first sample on; Sobol's second
// dimension comes from byte tables. All give exactly the numbers of the
// plain formulas (sobol(), nestedUniformScramble(), permuteQuads()).
#include <cassert>
#include <cstdint>

#include "stage/math_types.h"

namespace sdg {

// The draws' arithmetic, inline: the path tracer makes eight draws a vertex.
namespace sampler_detail {

constexpr uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(x);  // the bytes' order (gcc and clang)
}

// A seeded bijection of 32-bit words in which output bit k depends only on
// input bits 0..k (Laine and Karras 2011): adding, multiplying by an odd
// number and xor-ing with the word times an even number all carry
// information from low bits to high bits only. Applied to bit-reversed
// values it is a nested uniform scramble. The sequence of steps follows
// Burley 2020 and Vegdahl's later refinement (a seed-dependent odd
// multiplier, here passed in: sampler.cpp hashes it with the seed); the
// constants are this project's, chosen for flip bits that are unbiased and
// pairwise independent across prefixes to within sampling noise (measured
// over 20000 seeds on the first 7 digit levels).
constexpr uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed, uint32_t oddMultiplier) {
  x ^= x * 0x2a9e6f52u;
  x += seed;
  x *= oddMultiplier;
  x ^= x * 0x7b1c3ad4u;
  x ^= x * 0xd6e8feb6u;
  return x;
}

// Sobol's dimension 1 (Joe-Kuo's second, primitive polynomial x + 1): the
// direction numbers have m_k = 1 for all k by Bratley and Fox's recurrence
// m_k = 2 m_{k-1} xor m_{k-1}, so v_1 = 1/2, v_k = v_{k-1} xor v_{k-1} / 2,
// the rows of Pascal's triangle mod 2.
constexpr uint32_t sobolDimension1(uint32_t index) {
  uint32_t direction = 1u << 31;
  uint32_t result = 0;
  for (; index != 0; index >>= 1, direction ^= direction >> 1)
    if (index & 1u) result ^= direction;
  return result;
}

// The same, bit-reversed, by bytes of the index: the point is the xor of the
// direction numbers of the index's set bits (a linear map over GF(2), as is
// the reversal), so each byte's share can be looked up.
struct ReversedSobol1Tables {
  uint32_t byByte[4][256] = {};
  constexpr ReversedSobol1Tables() {
    for (uint32_t k = 0; k < 4; ++k)
      for (uint32_t b = 0; b < 256; ++b) byByte[k][b] = reverseBits(sobolDimension1(b << (8 * k)));
  }
  constexpr uint32_t operator()(uint32_t index) const {
    return byByte[0][index & 0xffu] ^ byByte[1][(index >> 8) & 0xffu] ^ byByte[2][(index >> 16) & 0xffu] ^
           byByte[3][index >> 24];
  }
};
inline constexpr ReversedSobol1Tables kReversedSobol1{};

// x's bits in the even bits, y's in the odd ones (both below 2^16): the
// Morton code, whose every aligned block of 4^k values is a 2^k x 2^k
// block of pixels.
constexpr uint32_t spreadBits(uint32_t v) {
  v &= 0xffffu;
  v = (v | (v << 8)) & 0x00ff00ffu;
  v = (v | (v << 4)) & 0x0f0f0f0fu;
  v = (v | (v << 2)) & 0x33333333u;
  return (v | (v << 1)) & 0x55555555u;
}
constexpr uint32_t morton(uint32_t x, uint32_t y) { return spreadBits(x) | (spreadBits(y) << 1); }

// The first step of the index shuffle, on the bit-reversed index: hands
// each 2 x 2 quad's four sub-blocks of indices to its pixels by one of all
// 24 permutations (as pbrt-v4's ZSobolSampler does with base-4 digits), where
// the nested base-2 scramble that follows alone gives 8. That scramble keeps
// a Morton digit's high bit's pair of pixels together in one half-block,
// always the same two (with y the high bit: side by side), so the error of a
// 4-sample frame came out in vertical stripes. Here each digit's half-block
// is picked by y, x or x xor y (the quad's rows, columns or diagonals pair
// up; probabilities 1/4, 1/4, 1/2, so rows and columns alike), chosen by two
// bits of a Laine-Karras hash that depend only on the higher digits; the
// scramble then flips the bits. A bijection that maps every aligned block of
// whole digits onto another one, so square pixel blocks stay nets.
// `highBits`: the digits' high bits' places in the reversed index
// (SampleLayout::quadHighBits).
constexpr uint32_t permuteQuads(uint32_t reversed, uint32_t highBits, uint32_t seed, uint32_t oddMultiplier) {
  // Bit k of `random` depends on bits below k of the reversed index only, the digits above in the index.
  const uint32_t random = laineKarrasPermutation(reversed, seed, oddMultiplier) ^ reversed;
  const uint32_t byX = random & highBits, diagonal = (random << 1) & highBits;
  const uint32_t y = reversed & highBits, x = (reversed >> 1) & highBits;
  const uint32_t picked = (x & byX) | (y & ~byX), other = x ^ y ^ picked;
  return (reversed & ~(highBits | (highBits << 1))) | (picked ^ (diagonal & other)) | (other << 1);
}

// 24 bits: every value is a float exactly, and the largest is below 1.
constexpr float toUnitFloat(uint32_t fixedPoint) { return static_cast<float>(fixedPoint >> 8) * 0x1p-24f; }

}  // namespace sampler_detail

// Where a frame's samples sit in the 32-bit Sobol index (see the header).
struct SampleLayout {
  static constexpr uint32_t kMaxTileBits = 6;  // 64 x 64-pixel tiles
  uint32_t sampleBits = 0;                     // ceil(log2(samples per pixel)), 0..32
  uint32_t tileBits = kMaxTileBits;            // a tile is 2^tileBits pixels a side

  constexpr explicit SampleLayout(uint32_t samplesPerPixel)
      : sampleBits(samplesPerPixel <= 1 ? 0u : 32u - uint32_t(__builtin_clz(samplesPerPixel - 1))),
        tileBits(sampleBits + 2 * kMaxTileBits <= 32 ? kMaxTileBits : (32 - sampleBits) / 2) {}
  // The high bits of the Morton code's base-4 digits (bit sampleBits + 2j + 1
  // of the index, j < tileBits) in the bit-reversed index: bit 30 - sampleBits - 2j.
  constexpr uint32_t quadHighBits() const {
    return tileBits == 0 ? 0u : (0x55555555u & ((1u << (2 * tileBits)) - 1u)) << (32 - sampleBits - 2 * tileBits);
  }
  // The index of pixel (x, y)'s first sample; sample s is indexBase | s.
  constexpr uint32_t indexBase(uint32_t x, uint32_t y) const {
    const uint32_t mask = (1u << tileBits) - 1u;
    return sampleBits >= 32 ? 0u : sampler_detail::morton(x & mask, y & mask) << sampleBits;
  }
};

// The scramble keys of one tile's slots in one frame, shared by the tile's
// pixel samplers: worked out for the first kCachedSlots slots when the tile
// is set, and by each draw beyond them.
class SamplerTile {
 public:
  // A slot's keys: the seeds of the index shuffle's two steps (the quads'
  // permutation, the nested scramble) and of each coordinate's scramble,
  // each with the odd multiplier of its hash.
  struct SlotKeys {
    uint32_t quads, quadsMultiplier;
    uint32_t shuffle, shuffleMultiplier;
    uint32_t x, xMultiplier;
    uint32_t y, yMultiplier;
  };
  // Slots whose keys a tile keeps: a path of the default 8 bounces draws 41.
  static constexpr uint32_t kCachedSlots = 48;

  SamplerTile() : SamplerTile(0, 1, 0, 0) {}
  // The tile holding pixel (x, y) in a frame of `samplesPerPixel` samples.
  SamplerTile(uint64_t frameSeed, uint32_t samplesPerPixel, uint32_t x, uint32_t y) {
    reset(frameSeed, samplesPerPixel, x, y);
  }
  // The same, reusing this object (no allocation).
  void reset(uint64_t frameSeed, uint32_t samplesPerPixel, uint32_t x, uint32_t y);

  const SampleLayout& layout() const { return layout_; }
  bool holds(uint32_t x, uint32_t y) const {
    return (x >> layout_.tileBits) == tileX_ && (y >> layout_.tileBits) == tileY_;
  }
  // A cached slot's keys (slot < kCachedSlots).
  const SlotKeys& cachedKeys(uint32_t slot) const { return cache_[slot]; }
  // Any slot's keys, worked out.
  void workOut(uint32_t slot, SlotKeys& keys) const;

 private:
  SampleLayout layout_{1};
  uint32_t tileX_ = 0, tileY_ = 0;
  uint64_t tileSeed_ = 0;
  SlotKeys cache_[kCachedSlots];
};

// One pixel's stream: its samples' indices and the slot drawn next; the keys
// are its tile's, which must outlive it.
class PixelSampler {
 public:
  // Pixel (x, y), which `tile` holds.
  PixelSampler(const SamplerTile& tile, uint32_t x, uint32_t y)
      : tile_(&tile),
        reversedPixel_(sampler_detail::reverseBits(tile.layout().indexBase(x, y))),
        quadHighBits_(tile.layout().quadHighBits()) {
    assert(tile.holds(x, y) && "a pixel's keys are its own tile's");
  }

  // Starts sample `index` (below the frame's samples per pixel) of this
  // pixel; the next draw is its first slot.
  void startSample(uint32_t index) {
    reversedSample_ = sampler_detail::reverseBits(index);
    slot_ = 0;
  }
  // The next slot's two coordinates, each in [0, 1).
  Vec2f next2D() {
    using namespace sampler_detail;
    uint32_t pixel;
    const SamplerTile::SlotKeys& keys = nextSlot(pixel);
    const uint32_t shuffled = shuffledIndex(pixel, keys);
    return {toUnitFloat(reverseBits(laineKarrasPermutation(shuffled, keys.x, keys.xMultiplier))),
            toUnitFloat(reverseBits(laineKarrasPermutation(kReversedSobol1(shuffled), keys.y, keys.yMultiplier)))};
  }
  // The next slot's first coordinate, in [0, 1).
  float next1D() {
    using namespace sampler_detail;
    uint32_t pixel;
    const SamplerTile::SlotKeys& keys = nextSlot(pixel);
    return toUnitFloat(reverseBits(laineKarrasPermutation(shuffledIndex(pixel, keys), keys.x, keys.xMultiplier)));
  }

 private:
  static constexpr uint32_t kCachedSlots = SamplerTile::kCachedSlots;

  // Steps on to the next slot: its keys (valid until the next draw) and,
  // in `pixel`, the pixel's reversed Morton code after the slot's quads'
  // permutation. The quads' permutation reads and writes the Morton digits
  // only, which lie above the sample's bits in the index: it depends on the
  // pixel and the slot, not the sample, so it is kept per slot.
  const SamplerTile::SlotKeys& nextSlot(uint32_t& pixel) {
    const uint32_t slot = slot_++;
    if (slot < cachedSlots_) {
      pixel = quads_[slot];
      return tile_->cachedKeys(slot);
    }
    return workOutSlot(slot, pixel);
  }
  const SamplerTile::SlotKeys& workOutSlot(uint32_t slot, uint32_t& pixel);
  // Scrambling the index (not just the values) shuffles which point each
  // sample gets, so two slots of one sample are not the same point twice,
  // and which sub-block of a block each pixel gets; it maps every aligned
  // block of whole base-4 Morton digits onto another such block, so the nets
  // survive. The formulas, with rev() the bit reversal, LK()
  // laineKarrasPermutation() and the keys' multipliers left out:
  //   shuffled = rev(LK(permuteQuads(rev(index), quads), shuffle))
  //   x = nestedUniformScramble(sobol(shuffled, 0), x) = rev(LK(shuffled, x)), as sobol(., 0) = rev()
  //   y = nestedUniformScramble(sobol(shuffled, 1), y) = rev(LK(rev(sobol(shuffled, 1)), y))
  // where permuteQuads(rev(index)) = pixel | rev(sample).
  uint32_t shuffledIndex(uint32_t pixel, const SamplerTile::SlotKeys& keys) const {
    using namespace sampler_detail;
    return reverseBits(laineKarrasPermutation(pixel | reversedSample_, keys.shuffle, keys.shuffleMultiplier));
  }

  const SamplerTile* tile_;
  uint32_t reversedPixel_;  // the pixel's first index, bit-reversed: its Morton code
  uint32_t quadHighBits_;
  uint32_t reversedSample_ = 0;
  uint32_t slot_ = 0;
  uint32_t cachedSlots_ = 0;       // slots [0, cachedSlots_) of quads_ are worked out
  uint32_t quads_[kCachedSlots];   // per slot: the pixel's reversed Morton code after the quads' permutation
  SamplerTile::SlotKeys scratch_;  // a slot beyond the cache
};

// The building blocks, exposed for the tests.

// Sobol point `index` in dimension 0 (van der Corput) or 1 (Joe-Kuo's
// second dimension, primitive polynomial x + 1), as a 0.32 fixed-point value.
uint32_t sobol(uint32_t index, int dimension);

// Owen's nested uniform scramble of a 0.32 fixed-point value: digit k (from
// the most significant) is flipped by a pseudo-random function of the seed
// (and the hash's odd multiplier) and the digits above it only.
uint32_t nestedUniformScramble(uint32_t value, uint32_t seed, uint32_t oddMultiplier);

}  // namespace sdg
