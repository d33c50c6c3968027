// Gaussian splats as a QNV stream (docs/splats.md, "QNV Gaussian streams"): each splat is
// a figure-6 record of Nagasawa's paper (position, the normal of its thinnest axis, A =
// importance, C = opacity) followed by words for its scales, rotation, colour and SH, and
// the stream is sorted by importance, largest first (the paper's magnitude order, here
// opacity times projected area), so every prefix is the best picture of its size and a
// progressive load shows the scene long before its last byte.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qnv/stream.hpp"
#include "splats/gaussian.hpp"
#include "splats/readers.hpp"

namespace gs::splats {

/// What encodeGaussianStream may give up for fewer bytes.
struct GaussianStreamOptions {
  /// Bits kept of each degree-1 SH code, 1..5 (5: all, step 1/16); each bit dropped
  /// doubles the step (4: 1/8, 3: 1/4 ...). Degree 2 and 3 codes (4 bits, step 1/8) drop
  /// as many, keeping at least one. The layout is unchanged, so every reader reads the
  /// stream; the coarser values are fewer distinct bytes, which zstd packs tighter
  /// (docs/splats.md, "Bytes and pictures"). Values outside 1..5 are clamped.
  int shBits = 5;
  /// The share of the splats, the most important first (the stream's order), that keep
  /// every SH bit whatever shBits says, 0..1.
  double shFullFraction = 0.0;
};

/// The records of `cloud` as a Gaussian stream (qnv::StreamKind::gaussian) in stream
/// order: by importance (splats::importance) largest first, ties in cloud order.
/// Splats of zero opacity or importance are left out. Header: the centres' box, the
/// importance range (logarithmic A), the natural-log range of the scales (valueMin,
/// valueMax), cloud.shDegree. Quantization (docs/splats.md): positions 12 bits per axis,
/// the thin axis' normal 6 + 7 bits, the major axis' angle about it 8 bits, log scales
/// 8 bits, opacity and DC colour 8 bits, SH degree 1 at 5 bits, higher at 4 bits.
/// header.packetBytes: whole splats, as many as fit 65528 bytes but at most 1/64 of the
/// cloud (at least 1,024: zstd needs room), so a progressive load of a large scene draws
/// after a few per cent of the bytes.
/// An empty cloud gives no records and a unit box. `options.shBits` below 5 rounds the SH
/// codes to coarser steps (lossy).
qnv::EncodedVectors encodeGaussianStream(const GaussianCloud& cloud,
                                         const GaussianStreamOptions& options = {});

/// The frame of a Gaussian stream of `cloud`, before its splats are ordered: which splats
/// it keeps (those encodeGaussianStream keeps, in cloud order), the importance of each as
/// quantized (qnv::gaussianImportance, square metres; same order), and the header
/// encodeGaussianStream writes but for vectorCount (0).
struct GaussianFrame {
  qnv::StreamHeader header;
  std::vector<std::uint32_t> kept;  // indices into the cloud
  std::vector<float> importance;    // per kept splat
};
GaussianFrame gaussianFrame(const GaussianCloud& cloud);

/// Whether a Gaussian stream keeps splat `i` of `cloud`: a peak opacity of at least half
/// an 8-bit step, an importance above 0, and finite centre, scales, band-0 colour and a
/// non-zero finite rotation.
bool keptInGaussianStream(const GaussianCloud& cloud, std::size_t i);

/// gaussianFrame's work on a scene read piecewise, batch after batch (an out-of-core
/// tileset encode: encode/src/ooc_gaussian.cpp), in two passes over the splats in scene
/// order. The header it finishes is gaussianFrame's for the whole scene, bit for bit.
class GaussianFrameBuilder {
 public:
  /// `shDegree` (clamped to 0..3) and `splatCount` (every splat of the scene, kept or not:
  /// it sizes the packets) are the scene's.
  GaussianFrameBuilder(int shDegree, std::uint64_t splatCount);
  /// Pass 1, every splat in scene order: true when it is kept (keptInGaussianStream);
  /// the kept splats' box and natural-log scale range grow by it; the header's colour
  /// space is the cloud's (qnv::StreamHeader::linearColor).
  bool addExtent(const GaussianCloud& cloud, std::size_t i);
  /// Between the passes: the box and the scale range fixed (a unit box when none is kept).
  void finishExtent();
  /// Pass 2, the kept splats only: the importance of splat `i` as quantized in the box
  /// and ranges (qnv::gaussianImportance, square metres); the importance range grows by it.
  float importanceOf(const GaussianCloud& cloud, std::size_t i);
  /// After pass 2: the header (vectorCount 0).
  const qnv::StreamHeader& finish();
  /// Splats kept in pass 1.
  std::uint64_t keptCount() const { return kept_; }
  /// The header as it stands (the box and ranges are final after finishExtent).
  const qnv::StreamHeader& header() const { return header_; }

 private:
  qnv::StreamHeader header_;
  std::uint64_t kept_ = 0;
  glm::vec3 lo_{INFINITY}, hi_{-INFINITY};
  float scaleLo_ = INFINITY, scaleHi_ = -INFINITY;
  float top_ = 0.0f, bottom_ = INFINITY;
};

/// The records of splats `order` of `cloud` (indices of splats gaussianFrame keeps, in the
/// order given, recordsPerElement() words each) quantized in `header`'s box, scale and
/// importance ranges (the splats' centres and scales should lie inside them; outside,
/// they are clamped). A is each quantized splat's importance code. `options` as for
/// encodeGaussianStream, shFullFraction counting the first splats of `order`. A QNV
/// tileset of Gaussians (splats/gaussian_tileset.hpp) writes every brick with it, the
/// brick's box in a header sharing the whole scene's ranges.
std::vector<std::uint64_t> encodeGaussianSplats(const GaussianCloud& cloud,
                                                std::span<const std::uint32_t> order,
                                                const qnv::StreamHeader& header,
                                                const GaussianStreamOptions& options = {});

/// The colour space of a Gaussian stream's splats (qnv::StreamHeader::linearColor).
inline ColorSpace colorSpaceOf(const qnv::StreamHeader& header) {
  return header.linearColor ? ColorSpace::linear : ColorSpace::srgb;
}

/// Appends the splats of `records` (whole splats of header.recordsPerElement() records,
/// as a Gaussian stream's packet gives them) to `cloud`, whose shDegree becomes the
/// header's when it is empty and whose colorSpace becomes the header's. Inverse of
/// encodeGaussianStream up to quantization. Safe for any words: every field decodes to a finite
/// splat.
void appendGaussianRecords(const qnv::StreamHeader& header, std::span<const std::uint64_t> records,
                           GaussianCloud& cloud);

/// Writes the splats of one packet's `records` (whole splats, as appendGaussianRecords
/// reads them) at their place in stream order: splats firstRecord / recordsPerElement()
/// on, growing `cloud` as needed (splats of packets not arrived yet have opacity 0, so
/// they draw nothing). A packet given twice lands on itself. Returns true when it wrote
/// over splats already present (a late or repeated packet).
bool placeGaussianRecords(const qnv::StreamHeader& header, std::uint64_t firstRecord,
                          std::span<const std::uint64_t> records, GaussianCloud& cloud);

/// Decodes a whole Gaussian stream (a .qnv file of kind 3) in memory with
/// qnv::StreamDecoder: damaged packets are skipped (their splats keep opacity 0: the
/// cloud keeps stream order), a cut-off stream gives what arrived. Throws FormatError naming `name`
/// when the header is rejected or the stream is of another kind.
GaussianCloud readQnvGaussians(std::string_view bytes, std::string_view name);

}  // namespace gs::splats
