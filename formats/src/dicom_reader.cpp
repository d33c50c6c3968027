// One DICOM file as a volume through GDCM (formats/dicom_reader.hpp): a walk over the
// element structure that bounds every length by the bytes left, then gdcm::ImageReader on
// a stream over the bytes, its decoded buffer rescaled to float.
#include <fcntl.h>
#include <gdcmDataSet.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmTrace.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <istream>
#include <memory>
#include <mutex>
#include <optional>
#include <streambuf>
#include <vector>

#include <glm/geometric.hpp>

#include "dicom_internal.hpp"

namespace gs::formats {

namespace detail {

namespace {

constexpr std::uint32_t kDicomUndefinedLength = 0xFFFFFFFFu;
constexpr int kDicomMaxDepth = 16;
// Compressed pixel data may not decode to more than this many bytes per byte of file
// (JPEG of a constant image reaches a few hundred), plus a fixed allowance.
constexpr std::uint64_t kDicomMaxRatio = 1024;
constexpr std::uint64_t kDicomRatioSlack = std::uint64_t{16} << 20;

// A read-only streambuf over bytes in memory, seekable, so GDCM reads without a copy.
class DicomViewBuf final : public std::streambuf {
 public:
  explicit DicomViewBuf(std::string_view bytes) {
    char* p = const_cast<char*>(bytes.data());
    setg(p, p, p + bytes.size());
  }

 protected:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    off_type base = 0;
    if (dir == std::ios_base::cur) base = gptr() - eback();
    if (dir == std::ios_base::end) base = egptr() - eback();
    return seekpos(pos_type(base + off), std::ios_base::in);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override {
    const off_type at = off_type(pos);
    if (at < 0 || at > egptr() - eback()) return pos_type(off_type(-1));
    setg(eback(), eback() + at, egptr());
    return pos;
  }
};

std::string dicomTagText(std::uint16_t g, std::uint16_t e) {
  char text[16];
  std::snprintf(text, sizeof text, "(%04X,%04X)", g, e);
  return text;
}

// The element walker of scanDicomFile.
class DicomWalker {
 public:
  DicomWalker(std::string_view bytes, const std::string& name) : b_(bytes), name_(name) {}

  DicomMeta run() {
    if (!hasDicomMagic(b_))
      throw InputError(name_ +
                       ": not a DICOM file (no 'DICM' at byte 128); expected a DICOM PS3.10 "
                       "file");
    std::size_t pos = 132;
    // File meta information: explicit VR little endian, group 0002.
    while (pos + 8 <= b_.size() && u16(pos, false) == 0x0002) {
      const Element el = header(pos, true, false);
      pos = el.value;
      checkLength(el, pos);
      const std::string_view value = b_.substr(pos, el.length);
      if (el.e == 0x0010) meta_.transferSyntax = trimUid(value);
      if (el.e == 0x0002) meta_.sopClass = trimUid(value);
      pos += el.length;
    }
    const std::string& ts = meta_.transferSyntax;
    if (ts == "1.2.840.10008.1.2.1.99")
      throw InputError(name_ +
                       ": deflated transfer syntax (1.2.840.10008.1.2.1.99) is not supported; "
                       "expected uncompressed, RLE, JPEG, JPEG-LS or JPEG 2000 pixel data");
    explicitVr_ = ts != "1.2.840.10008.1.2";
    big_ = ts == "1.2.840.10008.1.2.2";
    dataSet(pos, b_.size(), false, 0);
    return meta_;
  }

 private:
  struct Element {
    std::uint16_t g = 0, e = 0;
    char vr[2] = {0, 0};
    std::uint32_t length = 0;
    std::size_t start = 0, value = 0;  // offsets of the tag and of the value
  };

  std::uint16_t u16(std::size_t at, bool big) const {
    const auto* p = reinterpret_cast<const unsigned char*>(b_.data() + at);
    return big ? static_cast<std::uint16_t>(p[0] << 8 | p[1])
               : static_cast<std::uint16_t>(p[1] << 8 | p[0]);
  }
  std::uint32_t u32(std::size_t at, bool big) const {
    const std::uint32_t lo = u16(at, big), hi = u16(at + 2, big);
    return big ? (lo << 16 | hi) : (hi << 16 | lo);
  }
  static std::string trimUid(std::string_view v) {
    while (!v.empty() && (v.back() == '\0' || v.back() == ' ')) v.remove_suffix(1);
    return std::string(v.substr(0, 64));
  }
  [[noreturn]] void fail(std::size_t at, const std::string& what) const {
    throw InputError(name_ + ": " + what + " at byte " + std::to_string(at) +
                     "; the file is truncated or not DICOM");
  }

  Element header(std::size_t pos, bool explicitVr, bool big) const {
    if (b_.size() - pos < 8) fail(pos, "element header cut short");
    Element el;
    el.start = pos;
    el.g = u16(pos, big);
    el.e = u16(pos + 2, big);
    if (el.g == 0xFFFE || !explicitVr) {
      el.length = u32(pos + 4, big);
      el.value = pos + 8;
      return el;
    }
    el.vr[0] = b_[pos + 4];
    el.vr[1] = b_[pos + 5];
    if (el.vr[0] < 'A' || el.vr[0] > 'Z' || el.vr[1] < 'A' || el.vr[1] > 'Z')
      fail(pos, "element " + dicomTagText(el.g, el.e) + " without a value representation");
    // PS3.5 7.1.2: these value representations have a 4-byte length after 2 reserved bytes,
    // the others of PS3.5 table 6.2-1 a 2-byte length. Any other pair of letters is refused:
    // GDCM reads an unknown one with a 4-byte length, and the walk must read each element
    // as GDCM will, or a length it did not check reaches GDCM's allocation.
    static constexpr std::string_view kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                                 "SV", "UC", "UN", "UR", "UT", "UV"};
    static constexpr std::string_view kShort[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT",
                                                  "FD", "FL", "IS", "LO", "LT", "PN", "SH",
                                                  "SL", "SS", "ST", "TM", "UI", "UL", "US"};
    const std::string_view vr(el.vr, 2);
    if (std::find(std::begin(kLong), std::end(kLong), vr) != std::end(kLong)) {
      if (b_.size() - pos < 12) fail(pos, "element header cut short");
      el.length = u32(pos + 8, big);
      el.value = pos + 12;
    } else if (std::find(std::begin(kShort), std::end(kShort), vr) != std::end(kShort)) {
      el.length = u16(pos + 6, big);
      el.value = pos + 8;
    } else {
      fail(pos, "element " + dicomTagText(el.g, el.e) + " with the unknown value representation '" +
                    std::string(vr) + "'");
    }
    return el;
  }

  void checkLength(const Element& el, std::size_t pos) const {
    if (el.length != kDicomUndefinedLength && el.length > b_.size() - pos)
      throw InputError(name_ + ": element " + dicomTagText(el.g, el.e) + " at byte " +
                       std::to_string(el.start) + " claims " + std::to_string(el.length) +
                       " bytes, the file has " + std::to_string(b_.size() - pos) + " left");
  }

  bool itemAt(std::size_t pos, std::size_t end) const {
    return end - pos >= 8 && u16(pos, big_) == 0xFFFE && u16(pos + 2, big_) == 0xE000;
  }

  // Elements from `pos` to `end`; inside an undefined-length item, up to its delimiter.
  std::size_t dataSet(std::size_t pos, std::size_t end, bool inItem, int depth) {
    if (depth > kDicomMaxDepth) fail(pos, "sequences nested deeper than 16");
    while (pos < end) {
      const Element el = header(pos, explicitVr_, big_);
      pos = el.value;
      if (el.g == 0xFFFE) {
        if (el.e == 0xE00D && inItem) return pos;  // item delimitation
        fail(el.start, "misplaced item tag " + dicomTagText(el.g, el.e));
      }
      if (pos > end) fail(el.start, "element header runs past its item");
      const bool pixelData = el.g == 0x7FE0 && el.e == 0x0010 && depth == 0;
      const std::string_view vr(el.vr, 2);
      if (el.length == kDicomUndefinedLength) {
        if (pixelData) {
          meta_.hasPixelData = meta_.encapsulated = true;
          pos = fragments(pos, end);
        } else {
          const bool wasExplicit = explicitVr_;
          if (vr == "UN") explicitVr_ = false;  // PS3.5 6.2.2: implicit VR little endian
          pos = sequence(pos, end, depth + 1);
          explicitVr_ = wasExplicit;
        }
        continue;
      }
      if (el.length > end - pos)
        throw InputError(name_ + ": element " + dicomTagText(el.g, el.e) + " at byte " +
                         std::to_string(el.start) + " claims " + std::to_string(el.length) +
                         " bytes, the file has " + std::to_string(end - pos) + " left");
      if (pixelData) {
        meta_.hasPixelData = true;
        meta_.pixelDataBytes = el.length;
      } else if (vr == "SQ" || ((!explicitVr_ || vr == "UN") && itemAt(pos, pos + el.length))) {
        sequence(pos, pos + el.length, depth + 1);
      }
      pos += el.length;
    }
    if (inItem) fail(pos, "item without its delimiter");
    return pos;
  }

  // Items from `pos`: up to `end` (defined length) or to the sequence delimiter.
  std::size_t sequence(std::size_t pos, std::size_t end, int depth) {
    if (depth > kDicomMaxDepth) fail(pos, "sequences nested deeper than 16");
    while (pos < end) {
      if (end - pos < 8) fail(pos, "item header cut short");
      const std::uint16_t g = u16(pos, big_), e = u16(pos + 2, big_);
      const std::uint32_t length = u32(pos + 4, big_);
      const std::size_t start = pos;
      pos += 8;
      if (g == 0xFFFE && e == 0xE0DD) return pos;  // sequence delimitation
      if (g != 0xFFFE || e != 0xE000) fail(start, "expected an item, got " + dicomTagText(g, e));
      if (length == kDicomUndefinedLength) {
        pos = dataSet(pos, end, true, depth);
        continue;
      }
      if (length > end - pos)
        throw InputError(name_ + ": item at byte " + std::to_string(start) + " claims " +
                         std::to_string(length) + " bytes, its sequence has " +
                         std::to_string(end - pos) + " left");
      dataSet(pos, pos + length, false, depth);
      pos += length;
    }
    return pos;
  }

  // Encapsulated Pixel Data (PS3.5 A.4): items of defined length up to the delimiter.
  std::size_t fragments(std::size_t pos, std::size_t end) {
    while (pos < end) {
      if (end - pos < 8) fail(pos, "pixel data fragment cut short");
      const std::uint16_t g = u16(pos, big_), e = u16(pos + 2, big_);
      const std::uint32_t length = u32(pos + 4, big_);
      const std::size_t start = pos;
      pos += 8;
      if (g == 0xFFFE && e == 0xE0DD) return pos;
      if (g != 0xFFFE || e != 0xE000 || length > end - pos) fail(start, "bad pixel data fragment");
      pos += length;
    }
    fail(pos, "encapsulated pixel data without their delimiter");
  }

  std::string_view b_;
  const std::string& name_;
  bool explicitVr_ = true, big_ = false;
  DicomMeta meta_;
};

// The text value of `tag` in `ds`, trailing spaces and NULs removed; empty when absent.
std::string dicomString(const gdcm::DataSet& ds, std::uint16_t g, std::uint16_t e) {
  const gdcm::Tag tag(g, e);
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (!bv || !bv->GetPointer()) return {};
  std::string s(bv->GetPointer(), bv->GetLength());
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  std::size_t first = 0;
  while (first < s.size() && s[first] == ' ') ++first;
  return s.substr(first, 1024);
}

// The numbers of a DS or IS value ("a\b\c"); values that do not parse are skipped.
std::vector<double> dicomNumbers(const std::string& text) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size() && out.size() < 64) {
    const std::size_t end = std::min(text.find('\\', at), text.size());
    std::string part = text.substr(at, end - at);
    part.erase(0, part.find_first_not_of(' '));
    double v = 0.0;
    const char* first = part.data();
    if (!part.empty() && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, part.data() + part.size(), v);
    if (ec == std::errc() && ptr != first && std::isfinite(v)) out.push_back(v);
    at = end + 1;
  }
  return out;
}

std::optional<ScalarType> dicomScalarType(gdcm::PixelFormat::ScalarType t) {
  switch (t) {
    case gdcm::PixelFormat::UINT8:
      return ScalarType::uint8;
    case gdcm::PixelFormat::INT8:
      return ScalarType::int8;
    case gdcm::PixelFormat::UINT16:
      return ScalarType::uint16;
    case gdcm::PixelFormat::INT16:
      return ScalarType::int16;
    case gdcm::PixelFormat::UINT32:
      return ScalarType::uint32;
    case gdcm::PixelFormat::INT32:
      return ScalarType::int32;
    case gdcm::PixelFormat::UINT64:
      return ScalarType::uint64;
    case gdcm::PixelFormat::INT64:
      return ScalarType::int64;
    case gdcm::PixelFormat::FLOAT32:
      return ScalarType::float32;
    case gdcm::PixelFormat::FLOAT64:
      return ScalarType::float64;
    default:
      return std::nullopt;
  }
}

// While GDCM reads and decodes, stderr points at /dev/null: its codecs' libraries print
// on their own (libjpeg's "Unsupported JPEG data precision 12" when GDCM tries its 8-bit
// decoder on 12-bit data before the right one), past gdcm::Trace. Our errors say what
// failed. One reader at a time holds the redirection (a mutex), so nested or concurrent
// reads cannot restore the wrong descriptor.
class DicomQuietStderr {
 public:
  DicomQuietStderr() : lock_(mutex()) {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~DicomQuietStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
    }
  }
  DicomQuietStderr(const DicomQuietStderr&) = delete;
  DicomQuietStderr& operator=(const DicomQuietStderr&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  int saved_ = -1;
};

void quietGdcm() {
  static std::once_flag once;
  std::call_once(once, [] {
    gdcm::Trace::SetDebug(false);
    gdcm::Trace::SetWarning(false);
    gdcm::Trace::SetError(false);
  });
}

}  // namespace

DicomMeta scanDicomFile(std::string_view bytes, const std::string& name) {
  return DicomWalker(bytes, name).run();
}

DicomSlice readDicomSlice(std::string_view bytes, const std::string& name) {
  const DicomMeta meta = scanDicomFile(bytes, name);
  if (meta.sopClass == kDicomdirSopClass)
    throw InputError(name + ": a DICOMDIR, not an image; open it with loadDicom");
  if (!meta.hasPixelData)
    throw InputError(name + ": not a DICOM image (no Pixel Data (7FE0,0010))");
  quietGdcm();
  DicomViewBuf buf(bytes);
  std::istream in(&buf);
  // A reader whose GDCM call failed an assertion is leaked, never destroyed (its state is
  // unknown: runGdcmGuarded).
  auto owned = std::make_unique<gdcm::ImageReader>();
  gdcm::ImageReader& reader = *owned;
  reader.SetStream(in);
  struct ReadStep {
    gdcm::ImageReader* reader;
    bool read = false;
  } readStep{&reader};
  bool read = false;
  {
    const DicomQuietStderr quiet;
    read = runGdcmGuarded(
        [](void* p) {
          auto* s = static_cast<ReadStep*>(p);
          try {
            s->read = s->reader->Read();
          } catch (...) {
            s->read = false;
          }
        },
        &readStep);
  }
  if (!read) {
    leakGdcmObject(owned.release());
    throw InputError(name + ": GDCM cannot read this DICOM file (an internal check failed)");
  }
  read = readStep.read;
  if (!read)
    throw InputError(name + ": not a DICOM image GDCM can read (transfer syntax " +
                     (meta.transferSyntax.empty() ? "unknown" : meta.transferSyntax) + ")");
  const gdcm::Image& image = reader.GetImage();
  const gdcm::DataSet& ds = reader.GetFile().GetDataSet();
  const unsigned* d = image.GetDimensions();
  const std::uint64_t cols = d[0], rows = d[1];
  const std::uint64_t frames = image.GetNumberOfDimensions() >= 3 ? d[2] : 1;
  if (cols == 0 || rows == 0 || frames == 0 || cols > 65535 || rows > 65535)
    throw InputError(name + ": image of " + std::to_string(cols) + " x " + std::to_string(rows) +
                     " pixels, " + std::to_string(frames) +
                     " frames; expected 1..65535 columns and rows and at least one frame");
  const gdcm::PixelFormat& pf = image.GetPixelFormat();
  // GDCM asserts on some bit layouts, in GetScalarType and in the getters its header
  // defines (GetSamplesPerPixel, GetBitsStored, GetHighBit: live in builds without NDEBUG):
  // all asked under the guard.
  struct FormatStep {
    const gdcm::PixelFormat* format;
    unsigned samples = 0, bitsAllocated = 0;
    gdcm::PixelFormat::ScalarType type = gdcm::PixelFormat::UNKNOWN;
  } typeStep{&pf};
  bool typed = false;
  {
    const DicomQuietStderr quiet;  // GDCM prints its assertion before it fails it
    typed = runGdcmGuarded(
        [](void* p) {
          auto* s = static_cast<FormatStep*>(p);
          s->samples = s->format->GetSamplesPerPixel();
          s->bitsAllocated = s->format->GetBitsAllocated();
          s->type = s->format->GetScalarType();
        },
        &typeStep);
  }
  if (!typed) {
    leakGdcmObject(owned.release());
    throw InputError(name +
                     ": GDCM cannot read this DICOM file's pixel format (samples per pixel, "
                     "bits allocated, stored and high bit that do not fit together)");
  }
  if (typeStep.samples != 1)
    throw InputError(name + ": colour images (" + std::to_string(typeStep.samples) +
                     " samples per pixel) are not read as volumes; expected greyscale");
  const std::optional<ScalarType> type = dicomScalarType(typeStep.type);
  if (!type)
    throw InputError(name + ": pixel data of " + std::to_string(typeStep.bitsAllocated) +
                     " bits allocated are not supported; expected 8, 16, 32 or 64");
  const std::uint64_t voxels = cols * rows * frames;
  if (voxels > kMaxVoxels)
    throw InputError(name + ": " + std::to_string(voxels) + " voxels exceed the limit of " +
                     std::to_string(kMaxVoxels));
  const std::uint64_t need = voxels * scalarBytes(*type);
  if (!meta.encapsulated && need > meta.pixelDataBytes)
    throw InputError(name + ": expected " + std::to_string(need) + " bytes of pixel data for " +
                     std::to_string(cols) + " x " + std::to_string(rows) + " x " +
                     std::to_string(frames) + ", got " + std::to_string(meta.pixelDataBytes));
  if (meta.encapsulated && need > bytes.size() * kDicomMaxRatio + kDicomRatioSlack)
    throw InputError(name + ": " + std::to_string(bytes.size()) +
                     " bytes of compressed data cannot hold the " + std::to_string(need) +
                     " bytes of pixels the header describes");
  const unsigned long length = image.GetBufferLength();
  if (length != need)
    throw InputError(name + ": GDCM gives " + std::to_string(length) + " bytes of pixels, " +
                     std::to_string(need) + " expected (" + std::to_string(pf.GetBitsAllocated()) +
                     " bits allocated)");
  std::vector<char> raw(static_cast<std::size_t>(need));
  struct DecodeStep {
    const gdcm::Image* image;
    char* out;
    bool decoded = false;
  } decodeStep{&image, raw.data()};
  bool finished = false;
  {
    const DicomQuietStderr quiet;
    finished = runGdcmGuarded(
        [](void* p) {
          auto* s = static_cast<DecodeStep*>(p);
          try {
            s->decoded = s->image->GetBuffer(s->out);
          } catch (...) {
            s->decoded = false;
          }
        },
        &decodeStep);
  }
  if (!finished) leakGdcmObject(owned.release());
  const bool decoded = finished && decodeStep.decoded;
  if (!decoded)
    throw InputError(name + ": cannot decode pixel data in transfer syntax " + meta.transferSyntax +
                     "; the data are damaged or the codec is missing");

  DicomSlice s;
  DicomVolume& v = s.image;
  v.files = 1;
  v.transferSyntax = meta.transferSyntax;
  v.modality = dicomString(ds, 0x0008, 0x0060);
  v.rescaleType = dicomString(ds, 0x0028, 0x1054);
  // Modality LUT (PS3.3 C.11.1): the top-level attributes, else what GDCM found (the
  // per-frame functional groups of enhanced images).
  const std::vector<double> inter = dicomNumbers(dicomString(ds, 0x0028, 0x1052));
  const std::vector<double> slope = dicomNumbers(dicomString(ds, 0x0028, 0x1053));
  v.intercept = static_cast<float>(inter.empty() ? image.GetIntercept() : inter.front());
  v.slope = static_cast<float>(slope.empty() ? image.GetSlope() : slope.front());
  if (!std::isfinite(v.slope) || v.slope == 0.0f) v.slope = 1.0f;
  if (!std::isfinite(v.intercept)) v.intercept = 0.0f;
  if (v.rescaleType.empty() && v.modality == "CT") v.rescaleType = "HU";
  const std::vector<double> centers = dicomNumbers(dicomString(ds, 0x0028, 0x1050));
  const std::vector<double> widths = dicomNumbers(dicomString(ds, 0x0028, 0x1051));
  std::vector<std::string> explanations;
  {
    const std::string text = dicomString(ds, 0x0028, 0x1055);
    for (std::size_t at = 0; !text.empty() && at <= text.size() && explanations.size() < 64;) {
      const std::size_t end = std::min(text.find('\\', at), text.size());
      explanations.push_back(text.substr(at, end - at));
      at = end + 1;
    }
  }
  for (std::size_t i = 0; i < std::min(centers.size(), widths.size()); ++i) {
    if (!(widths[i] > 0.0)) continue;
    DicomWindow w{static_cast<float>(centers[i]), static_cast<float>(widths[i]), {}};
    if (i < explanations.size()) w.explanation = explanations[i];
    v.windows.push_back(std::move(w));
  }

  const std::vector<double> ipp = dicomNumbers(dicomString(ds, 0x0020, 0x0032));
  const std::vector<double> iop = dicomNumbers(dicomString(ds, 0x0020, 0x0037));
  s.hasPosition = ipp.size() == 3;
  if (s.hasPosition) s.position = {ipp[0], ipp[1], ipp[2]};
  const double* o = image.GetOrigin();
  if (!s.hasPosition && frames > 1) s.position = {o[0], o[1], o[2]};
  const double* dc = image.GetDirectionCosines();
  glm::dvec3 row{dc[0], dc[1], dc[2]}, col{dc[3], dc[4], dc[5]};
  if (iop.size() == 6) row = {iop[0], iop[1], iop[2]}, col = {iop[3], iop[4], iop[5]};
  s.hasOrientation = iop.size() == 6;
  if (!(glm::length(row) > 0.5 && glm::length(col) > 0.5 &&
        glm::length(glm::cross(row, col)) > 0.5))
    row = {1, 0, 0}, col = {0, 1, 0};
  s.row = glm::normalize(row);
  s.column = glm::normalize(col);
  const glm::dvec3 n = glm::normalize(glm::cross(s.row, s.column));
  v.rowDirection = glm::vec3(s.row);
  v.columnDirection = glm::vec3(s.column);
  v.sliceDirection = glm::vec3(-n) + glm::vec3(0.0f);  // no -0 in what is printed
  s.seriesUid = dicomString(ds, 0x0020, 0x000E).substr(0, 64);
  const std::vector<double> instance = dicomNumbers(dicomString(ds, 0x0020, 0x0013));
  if (!instance.empty() && std::abs(instance.front()) < 1e15)
    s.instance = static_cast<long long>(instance.front());
  const std::vector<double> thick = dicomNumbers(dicomString(ds, 0x0018, 0x0050));
  const std::vector<double> between = dicomNumbers(dicomString(ds, 0x0018, 0x0088));
  if (!thick.empty() && thick.front() > 0.0) s.thickness = thick.front();
  if (!between.empty() && between.front() > 0.0) s.between = between.front();
  s.sopClass = meta.sopClass;

  Volume& vol = v.volume;
  vol.dims = {static_cast<std::uint32_t>(cols), static_cast<std::uint32_t>(rows),
              static_cast<std::uint32_t>(frames)};
  vol.sourceType = *type;
  const double* sp = image.GetSpacing();
  // Pixel Spacing (PS3.3 C.7.6.2.1.1): row spacing (y), then column spacing (x); GDCM's
  // when absent (Imager Pixel Spacing, enhanced images' Pixel Measures).
  const std::vector<double> ps = dicomNumbers(dicomString(ds, 0x0028, 0x0030));
  const double spacingX = ps.size() == 2 && ps[1] > 0.0 ? ps[1] : sp[0];
  const double spacingY = ps.size() == 2 && ps[0] > 0.0 ? ps[0] : sp[1];
  const auto spacingOr1 = [](double x) {
    return std::isfinite(x) && x > 0.0 && x < 1e6 ? static_cast<float>(x) : 1.0f;
  };
  double zStep = s.between > 0.0 ? s.between : s.thickness;
  if (frames > 1 && sp[2] > 0.0 && sp[2] != 1.0) zStep = sp[2];  // GDCM: frame positions
  vol.spacing = {spacingOr1(spacingX), spacingOr1(spacingY), spacingOr1(zStep)};
  vol.origin = glm::vec3(s.position);
  vol.samples.resize(static_cast<std::size_t>(voxels));
  convertSamples(raw.data(), vol.samples.size(), *type, std::endian::native == std::endian::big,
                 vol.samples.data());
  // Frames are stored in file order; multi-frame files keep it (see dicom_reader.hpp).
  if (v.slope != 1.0f || v.intercept != 0.0f)
    for (float& x : vol.samples) x = x * v.slope + v.intercept;
  return s;
}

}  // namespace detail

bool hasDicomMagic(std::string_view head) {
  return head.size() >= 132 && head.substr(128, 4) == "DICM";
}

DicomVolume detail::readDicomHere(std::string_view bytes, const std::string& name) {
  return readDicomSlice(bytes, name).image;
}

}  // namespace gs::formats
